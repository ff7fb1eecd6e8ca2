// Device buffers kept across users (vk/recycled_buffers.hpp) on a real Vulkan device (lavapipe in
// CI): sizes go to power-of-two classes, a returned buffer serves the next request of its class,
// large ones and those past the kept bytes are freed, a buffer outliving its recycler is freed,
// threads take and return side by side, and a new scene's acceleration structures go into the
// storage an earlier scene gave back once the GPU is done with it.
#include <gtest/gtest.h>

#include <memory>
#include <thread>
#include <vector>

#include "scene/scene.hpp"
#include "vk/acceleration_scene.hpp"
#include "vk/acceleration_structure.hpp"
#include "vk/recycled_buffers.hpp"
#include "vk/vulkan_device.hpp"
#include "vulkan_device_test.hpp"

namespace {

using lgh::vk::RecycledBuffers;
constexpr ::vk::DeviceSize kMin = RecycledBuffers::kMinBytes;
constexpr ::vk::DeviceSize kMax = RecycledBuffers::kMaxRecycledBytes;

class RecycledBuffersTest : public lgh::test::VulkanDeviceTest {
 protected:
  std::shared_ptr<RecycledBuffers> recycler() const {
    return RecycledBuffers::create(*device, lgh::vk::accelerationStorage(0));
  }
};

TEST(RecycledBufferClasses, PowersOfTwoFromTheSmallestClassUpToTheLargestKept) {
  EXPECT_EQ(RecycledBuffers::classOf(0), kMin);
  EXPECT_EQ(RecycledBuffers::classOf(1), kMin);
  EXPECT_EQ(RecycledBuffers::classOf(kMin), kMin);
  EXPECT_EQ(RecycledBuffers::classOf(kMin + 1), 2 * kMin);
  EXPECT_EQ(RecycledBuffers::classOf(3 * kMin), 4 * kMin);
  EXPECT_EQ(RecycledBuffers::classOf(kMax), kMax);
  EXPECT_EQ(RecycledBuffers::classOf(kMax + 1), kMax + 1) << "above the classes: the exact size";
}

TEST_F(RecycledBuffersTest, AReturnedBufferServesTheNextRequestOfItsClass) {
  const auto buffers = recycler();
  auto first = buffers->take(1000);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->size(), kMin);
  EXPECT_NE(first->address(), 0U) << "structure storage has a device address";
  const ::vk::Buffer handle = first->handle();
  first.reset();
  EXPECT_EQ(buffers->stats().kept, 1U);
  EXPECT_EQ(buffers->stats().keptBytes, kMin);

  const auto again = buffers->take(kMin - 1);
  EXPECT_EQ(again->handle(), handle);
  const auto larger = buffers->take(kMin + 1);
  EXPECT_NE(larger->handle(), handle);
  EXPECT_EQ(larger->size(), 2 * kMin);
  const RecycledBuffers::Stats stats = buffers->stats();
  EXPECT_EQ(stats.taken, 3U);
  EXPECT_EQ(stats.recycled, 1U);
  EXPECT_EQ(stats.kept, 0U);
}

TEST_F(RecycledBuffersTest, LargeBuffersAndThoseBeyondTheKeptBytesAreFreed) {
  const auto buffers = recycler();
  buffers->take(kMax + 1).reset();
  EXPECT_EQ(buffers->stats().kept, 0U) << "a buffer above the largest class is not kept";

  std::vector<std::shared_ptr<const lgh::vk::DeviceBuffer>> held;
  const std::size_t fitting = RecycledBuffers::kKeptBytes / kMax;
  for (std::size_t i = 0; i < fitting + 2; ++i) held.push_back(buffers->take(kMax));
  held.clear();
  EXPECT_EQ(buffers->stats().kept, fitting);
  EXPECT_EQ(buffers->stats().keptBytes, RecycledBuffers::kKeptBytes);
}

TEST_F(RecycledBuffersTest, ABufferThatOutlivesItsRecyclerIsFreed) {
  auto buffers = recycler();
  auto buffer = buffers->take(1);
  buffers.reset();
  EXPECT_EQ(buffer->size(), kMin) << "still usable after the recycler is gone";
  buffer.reset();  // freed, not given back (AddressSanitizer and the Vulkan driver watch this)
}

TEST_F(RecycledBuffersTest, ThreadsTakeAndReturnSideBySide) {
  const auto buffers = recycler();
  constexpr int kThreads = 4;
  constexpr int kRounds = 50;
  std::vector<std::thread> threads;
  threads.reserve(kThreads);
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&buffers, t] {
      for (int round = 0; round < kRounds; ++round) {
        const auto buffer = buffers->take(kMin << static_cast<unsigned>((t + round) % 3));
        EXPECT_GE(buffer->size(), kMin);
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  const RecycledBuffers::Stats stats = buffers->stats();
  EXPECT_EQ(stats.taken, std::size_t{kThreads} * kRounds);
  EXPECT_GT(stats.recycled, 0U);
  // Every buffer made is back (far below the kept bytes): those made are those not recycled.
  EXPECT_EQ(stats.kept, stats.taken - stats.recycled);
  EXPECT_LE(stats.keptBytes, RecycledBuffers::kKeptBytes);
}

lgh::Scene triangleScene() {
  lgh::Primitive primitive;
  for (const glm::vec3 position : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}) {
    primitive.vertices.push_back({.position = position});
  }
  primitive.indices = {0, 1, 2};
  lgh::Scene scene;
  scene.name = "triangle";
  scene.meshes.emplace_back().primitives.push_back(std::move(primitive));
  scene.instances.push_back({.mesh = 0, .world = glm::mat4(1.0F)});
  return scene;
}

TEST_F(RecycledBuffersTest, ANewScenesStructuresGoWhereAnEarlierScenesWere) {
  lgh::vk::RecycledBuffers& storage = device->structureStorage();
  const lgh::Scene scene = triangleScene();
  auto first = lgh::vk::AccelerationScene::build(device, scene);
  ASSERT_NE(first, nullptr);
  const RecycledBuffers::Stats before = storage.stats();
  first.reset();  // a deferred release: the storage comes back once the queue is done with it
  device->waitIdle();
  device->deferredRelease().collect();
  EXPECT_EQ(storage.stats().kept, before.kept + 1);

  const auto second = lgh::vk::AccelerationScene::build(device, scene);
  const RecycledBuffers::Stats after = storage.stats();
  EXPECT_EQ(after.taken, before.taken + 1);
  EXPECT_EQ(after.recycled, before.recycled + 1);
  EXPECT_GT(second->gpuBytes(), 0U);
}

}  // namespace
