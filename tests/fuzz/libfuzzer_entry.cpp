// One libFuzzer binary per target: compiled once per target with LGH_FUZZ_TARGET naming the
// body in fuzz_targets.hpp.
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  lgh::fuzz::setUpQuietLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  lgh::fuzz::LGH_FUZZ_TARGET(data, size);
  return 0;
}
