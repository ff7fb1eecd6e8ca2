// Names the calling thread as `top -H`, `perf` and /proc/<pid>/task/<tid>/comm show it, so that
// an operator (or a profile) can tell lghd's render, encoder, prefetch and other threads apart
// from each other and from the driver's (llvmpipe-N, ...).
#pragma once

#include <string_view>

namespace lgh {

// Linux keeps 15 bytes of a thread's name: a longer one is cut there.
void nameThisThread(std::string_view name);

}  // namespace lgh
