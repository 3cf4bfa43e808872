#include "app/heap_tuning.h"

#include <cstdlib>  // defines __GLIBC__ on glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace candela {

void keep_freed_heap_memory() {
#if defined(__GLIBC__)
  // Blocks up to 32 MiB from the heap rather than their own mappings (a
  // mapping is returned on free), and the heap's top trimmed only past
  // 256 MiB. Setting either also stops glibc's own adjusting of them.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

}  // namespace candela
