#include "vk/fence_wait.hpp"

#include <chrono>
#include <cstdint>

#include <fmt/format.h>

#include "lgh/error.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

// Far beyond any batch on a GPU, and beyond the largest a test gives lavapipe.
constexpr std::chrono::seconds kFenceTimeout{300};

}  // namespace

void waitForFence(const VulkanDevice& device, ::vk::Fence fence, std::string_view work) {
  const auto timeout = static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(kFenceTimeout).count());
  if (device.device().waitForFences(fence, VK_TRUE, timeout) == ::vk::Result::eTimeout) {
    throw Error(ErrorCode::Internal,
                fmt::format("{} did not finish within {} s (did GL never signal the semaphore "
                            "the trace waits on?)",
                            work, kFenceTimeout.count()));
  }
}

}  // namespace lgh::vk
