// The acceleration-structure builds' transient buffers (vk/transient_buffers.hpp) on a real
// Vulkan device (lavapipe in CI): one buffer per kind, handed out again while it is large enough,
// grown when it is not, and not kept far larger than needed once past the kept size.
#include <gtest/gtest.h>

#include "vk/transient_buffers.hpp"
#include "vk/vulkan_device.hpp"
#include "vulkan_device_test.hpp"

namespace {

using lgh::vk::BufferSpec;
using lgh::vk::MemoryKind;
using lgh::vk::TransientBuffers;

class TransientBuffersTest : public lgh::test::VulkanDeviceTest {
 protected:
  static BufferSpec staging(::vk::DeviceSize size) {
    return {.size = size,
            .usage = ::vk::BufferUsageFlagBits::eTransferSrc,
            .memory = MemoryKind::HostVisible};
  }
  static BufferSpec scratch(::vk::DeviceSize size) {
    return {.size = size,
            .usage = ::vk::BufferUsageFlagBits::eStorageBuffer,
            .memory = MemoryKind::DeviceLocal,
            .deviceAddress = true,
            .addressAlignment = 256};
  }
};

TEST_F(TransientBuffersTest, OneBufferPerKindHandedOutWhileLargeEnough) {
  TransientBuffers buffers;
  const lgh::vk::DeviceBuffer& first = buffers.get(*device, staging(4096));
  EXPECT_GE(first.size(), 4096U);
  EXPECT_NE(first.mapped(), nullptr);
  EXPECT_EQ(&buffers.get(*device, staging(1000)), &first);
  const lgh::vk::DeviceBuffer& other = buffers.get(*device, scratch(1000));
  EXPECT_NE(&other, &first);
  EXPECT_EQ(other.address() % 256, 0U);
  EXPECT_EQ(buffers.get(*device, staging(1000)).handle(), first.handle());
}

TEST_F(TransientBuffersTest, GrowsWhenTooSmallAndDropsAHugeOneForASmallNeed) {
  TransientBuffers buffers;
  EXPECT_GE(buffers.get(*device, staging(1000)).size(), 1000U);
  const ::vk::DeviceSize huge = 2 * TransientBuffers::kKeptBytes;
  EXPECT_GE(buffers.get(*device, staging(huge)).size(), huge);
  // Half of it still reuses the huge one; a small need gets a buffer of its own size.
  EXPECT_GE(buffers.get(*device, staging(huge / 2)).size(), huge);
  EXPECT_LT(buffers.get(*device, staging(1000)).size(), TransientBuffers::kKeptBytes);
}

}  // namespace
