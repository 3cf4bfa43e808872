// The C library's heap, set for a renderer. Mesa's software rasteriser (and
// its vertex stage on any driver) allocates and frees large buffers every
// draw; glibc hands blocks over its thresholds back to the kernel at once
// and the next draw faults every page in again: with 100 candles a third of
// the frame went to page faults. Kept, the freed memory is reused.
#pragma once

namespace candela {

// Call once, first thing in main(). A no-op outside glibc.
void keep_freed_heap_memory();

}  // namespace candela
