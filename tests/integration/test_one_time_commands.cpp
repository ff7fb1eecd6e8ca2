// The device's one-time submissions (vk/one_time_commands.hpp) on a real Vulkan device (lavapipe
// in CI): a submission that is not waited for is retired, its callback run, by the next one or by
// retire(); submitAndWait retires its own.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "context/gl_context.hpp"
#include "gl/gl_api.hpp"
#include "lgh/error.hpp"
#include "test_support.hpp"
#include "vk/one_time_commands.hpp"
#include "vk/vulkan_device.hpp"

namespace {

class OneTimeCommandsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context = lgh::GlContext::create(lgh::test::rendererOptions());
    lgh::vk::DeviceUuid uuid{};
    glGetUnsignedBytei_vEXT(GL_DEVICE_UUID_EXT, 0, uuid.data());
    try {
      device = lgh::vk::VulkanDevice::create(uuid);
    } catch (const lgh::Error& error) {
      skipReason = error.what();
    }
  }
  static void TearDownTestSuite() {
    device.reset();
    context.reset();
  }
  void SetUp() override {
    if (device == nullptr) GTEST_SKIP() << "no Vulkan device: " << skipReason;
  }

  static void timestampsOnly(const ::vk::raii::CommandBuffer& commands) {
    device->oneTimeCommands().timestamps().begin(commands, 0);
    device->oneTimeCommands().timestamps().end(commands, 0);
  }

  static inline std::unique_ptr<lgh::GlContext> context;
  static inline std::shared_ptr<lgh::vk::VulkanDevice> device;
  static inline std::string skipReason;
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
