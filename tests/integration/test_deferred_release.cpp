// The deferred release of objects the GPU may still use (vk/deferred_release.hpp) on a real Vulkan
// device (lavapipe in CI): held while work submitted before the release runs, destroyed once it
// is done, by a later collect() or release() or by the owner's destruction, never waited for.
#include <gtest/gtest.h>

#include <memory>

#include "vk/deferred_release.hpp"
#include "vk/vulkan_device.hpp"
#include "vulkan_device_test.hpp"

namespace {

using lgh::vk::DeferredRelease;

class DeferredReleaseTest : public lgh::test::VulkanDeviceTest {
 protected:
  // Something to hold whose destruction the test sees.
  static std::shared_ptr<void> tracked(bool& destroyed) {
    destroyed = false;
    return {new int(0), [&destroyed](int* value) {
              destroyed = true;
              delete value;
            }};
  }
};

// Work on the queue that waits for the host to set an event: in flight until the test says so.
class BlockedQueue {
 public:
  explicit BlockedQueue(const lgh::vk::VulkanDevice& device)
      : device_(device),
        event_(device.device(), ::vk::EventCreateInfo{}),
        pool_(device.device(),
              ::vk::CommandPoolCreateInfo{.queueFamilyIndex = device.queueFamily()}),
        buffers_(device.device(),
                 ::vk::CommandBufferAllocateInfo{.commandPool = *pool_,
                                                 .level = ::vk::CommandBufferLevel::ePrimary,
                                                 .commandBufferCount = 1}) {
    const ::vk::raii::CommandBuffer& commands = buffers_.front();
    commands.begin({});
    commands.waitEvents(*event_, ::vk::PipelineStageFlagBits::eHost,
                        ::vk::PipelineStageFlagBits::eAllCommands, {}, {}, {});
    commands.end();
    const ::vk::CommandBuffer handle = *commands;
    device.queue().submit(::vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &handle});
  }
  ~BlockedQueue() { unblock(); }
  BlockedQueue(const BlockedQueue&) = delete;
  BlockedQueue& operator=(const BlockedQueue&) = delete;

  void unblock() {
    if (done_) return;
    event_.set();
    device_.queue().waitIdle();
    done_ = true;
  }

 private:
  const lgh::vk::VulkanDevice& device_;
  ::vk::raii::Event event_;
  ::vk::raii::CommandPool pool_;
  ::vk::raii::CommandBuffers buffers_;
  bool done_ = false;
};

TEST_F(DeferredReleaseTest, HeldWhileEarlierWorkRunsAndDestroyedOnceItIsDone) {
  DeferredRelease release(*device);
  bool destroyed = false;
  BlockedQueue blocked(*device);
  release.release(tracked(destroyed));
  release.collect();
  EXPECT_FALSE(destroyed) << "destroyed while work submitted before its release still ran";
  EXPECT_EQ(release.pending(), 1U);
  blocked.unblock();
  release.collect();
  EXPECT_TRUE(destroyed);
  EXPECT_EQ(release.pending(), 0U);
}

TEST_F(DeferredReleaseTest, ALaterReleaseDestroysWhatIsDone) {
  DeferredRelease release(*device);
  bool first = false;
  bool second = false;
  release.release(tracked(first));
  device->queue().waitIdle();
  release.release(tracked(second));
  EXPECT_TRUE(first);
  device->queue().waitIdle();
  release.collect();
  EXPECT_TRUE(second);
}

TEST_F(DeferredReleaseTest, TheOwnersDestructionWaitsAndDestroysTheRest) {
  bool destroyed = false;
  {
    auto release = std::make_unique<DeferredRelease>(*device);
    BlockedQueue blocked(*device);
    release->release(tracked(destroyed));
    EXPECT_FALSE(destroyed);
    blocked.unblock();  // else the destructor's wait for the device would never end
    release.reset();
  }
  EXPECT_TRUE(destroyed);
}

TEST_F(DeferredReleaseTest, NeverHoldsMoreThanItsLimitWhileTheQueueMovesOn) {
  DeferredRelease release(*device);
  for (std::size_t i = 0; i < 3 * DeferredRelease::kMaxPending; ++i) {
    release.release(std::make_shared<int>(static_cast<int>(i)));
    EXPECT_LE(release.pending(), DeferredRelease::kMaxPending + 1);
  }
  device->queue().waitIdle();
  release.collect();
  EXPECT_EQ(release.pending(), 0U);
}

}  // namespace
