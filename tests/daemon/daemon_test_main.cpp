// main() of the daemon tests. The render queue probes Vulkan by running its own executable
// (/proc/self/exe) with --probe-vulkan, as lghd does; in a test that executable is the test
// binary, so it answers that flag the way lghd's main does rather than run the tests again.
#include <gtest/gtest.h>

#include <string_view>

#include "logging.hpp"
#include "vulkan_probe_process.hpp"

int main(int argc, char** argv) {
  if (argc == 2 && std::string_view(argv[1]) == lghd::kProbeVulkanFlag) {
    return lghd::printVulkanProbe();
  }
  // The daemon's logger, as lghd sets it up, quieter: warnings and errors only, as text.
  lghd::logging::setUp("warn", "text");
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
