// keep_freed_heap_memory(): a renderer's large, short-lived buffers come from
// the heap and stay there when freed, instead of a fresh mapping (every page
// faulted in again) per draw.
#include "app/heap_tuning.h"

#include <gtest/gtest.h>

#include <cstdlib>  // defines __GLIBC__ on glibc
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace candela {
namespace {

// ASan's allocator stands in for glibc's there: its mallopt and mallinfo2
// do nothing.
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
TEST(HeapTuning, LargeBlocksComeFromTheHeapAndStay) {
  keep_freed_heap_memory();
  const size_t mapped_before = mallinfo2().hblks;
  // 8 MiB: glibc's default would give it a mapping of its own (over 128 KiB).
  constexpr size_t kBlock = 8 << 20;
  void* p = std::malloc(kBlock);
  ASSERT_NE(p, nullptr);
  std::memset(p, 1, kBlock);
  EXPECT_EQ(mallinfo2().hblks, mapped_before) << "the block was given a mapping of its own";
  std::free(p);
  // Freed, it stays with the process: the heap still holds it for the next draw.
  EXPECT_GE(mallinfo2().fordblks + mallinfo2().keepcost, kBlock);
}
#endif

}  // namespace
}  // namespace candela
