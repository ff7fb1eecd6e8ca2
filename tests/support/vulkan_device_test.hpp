// A test suite on the tracer's Vulkan device of this machine's GL device (lavapipe beside
// llvmpipe in CI): one GL context and one VulkanDevice for the suite, every test skipped, with the
// reason, where there is no Vulkan device.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "context/gl_context.hpp"
#include "gl/gl_api.hpp"
#include "lgh/error.hpp"
#include "test_support.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::test {

class VulkanDeviceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context = GlContext::create(rendererOptions());
    vk::DeviceUuid uuid{};
    glGetUnsignedBytei_vEXT(GL_DEVICE_UUID_EXT, 0, uuid.data());
    try {
      device = vk::VulkanDevice::create(uuid);
    } catch (const Error& error) {
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

  static inline std::unique_ptr<GlContext> context;
  static inline std::shared_ptr<vk::VulkanDevice> device;
  static inline std::string skipReason;
};

}  // namespace lgh::test
