// The device's one-time submissions (vk/one_time_commands.hpp) on a real Vulkan device (lavapipe
// in CI): a submission that is not waited for is retired, its callback run, by the next one or by
// retire(); submitAndWait retires its own.
#include <gtest/gtest.h>

#include "vk/one_time_commands.hpp"
#include "vk/vulkan_device.hpp"
#include "vulkan_device_test.hpp"

namespace {

class OneTimeCommandsTest : public lgh::test::VulkanDeviceTest {
 protected:
  static void timestampsOnly(const ::vk::raii::CommandBuffer& commands) {
    device->oneTimeCommands().timestamps().begin(commands, 0);
    device->oneTimeCommands().timestamps().end(commands, 0);
  }
};

TEST_F(OneTimeCommandsTest, ASubmissionNotWaitedForIsRetiredByRetire) {
  lgh::vk::OneTimeCommands& commands = device->oneTimeCommands();
  double gpuMs = -1.0;
  commands.submit(*device, timestampsOnly, [&] { gpuMs = commands.timestamps().elapsedMs(0); });
  EXPECT_EQ(gpuMs, -1.0) << "retired before anybody asked";
  commands.retire(*device);
  EXPECT_GE(gpuMs, 0.0);
  commands.retire(*device);  // nothing pending: nothing happens
}

TEST_F(OneTimeCommandsTest, TheNextSubmissionRetiresThePendingOne) {
  lgh::vk::OneTimeCommands& commands = device->oneTimeCommands();
  int retired = 0;
  commands.submit(*device, timestampsOnly, [&] { ++retired; });
  commands.submit(*device, timestampsOnly, [&] { retired += 10; });
  EXPECT_EQ(retired, 1);
  commands.submitAndWait(*device, timestampsOnly);
  EXPECT_EQ(retired, 11);
}

}  // namespace
