#include "allocator_tuning.hpp"

#include <malloc.h>

namespace lgh {

void keepFreedMemoryForReuse() {
  // Blocks up to 32 MiB (glibc's largest mmap threshold) come from the heap, not from mmap.
  constexpr int kMmapThreshold = 32 << 20;
  // The heap is trimmed back to the system only above 512 MiB free at its top.
  constexpr int kTrimThreshold = 512 << 20;
  // mallopt returns 0 on a value it refuses: glibc's defaults then stay, which is only slower.
  mallopt(M_MMAP_THRESHOLD, kMmapThreshold);
  mallopt(M_TRIM_THRESHOLD, kTrimThreshold);
}

}  // namespace lgh
