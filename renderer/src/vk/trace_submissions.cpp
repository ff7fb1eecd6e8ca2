#include "vk/trace_submissions.hpp"

#include "vk/fence_wait.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

std::vector<::vk::raii::Fence> createFences(const ::vk::raii::Device& device, std::uint32_t n) {
  std::vector<::vk::raii::Fence> fences;
  fences.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) fences.emplace_back(device, ::vk::FenceCreateInfo{});
  return fences;
}

}  // namespace

TraceSubmissions::TraceSubmissions(const VulkanDevice& device, std::uint32_t slots)
    : device_(&device),
      pool_(
          device.device(),
          ::vk::CommandPoolCreateInfo{.flags = ::vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                      .queueFamilyIndex = device.queueFamily()}),
      commands_(device.device(),
                ::vk::CommandBufferAllocateInfo{.commandPool = *pool_,
                                                .level = ::vk::CommandBufferLevel::ePrimary,
                                                .commandBufferCount = slots}),
      fences_(createFences(device.device(), slots)),
      inFlight_(slots, false),
      timestamps_(device, slots),
      numberOf_(slots, 0) {}

std::uint32_t TraceSubmissions::acquire() {
  const std::uint32_t slot = next_;
  next_ = (next_ + 1) % static_cast<std::uint32_t>(fences_.size());
  retire(slot);
  device_->device().resetFences(*fences_[slot]);
  commands_[slot].reset();
  return slot;
}

void TraceSubmissions::submit(std::uint32_t slot, ::vk::Semaphore wait,
                              ::vk::PipelineStageFlags waitStage, ::vk::Semaphore signal) {
  device_->submit(*commands_[slot], *fences_[slot], wait, waitStage, signal);
  inFlight_[slot] = true;
  numberOf_[slot] = ++submitted_;
}

void TraceSubmissions::retire(std::uint32_t slot) {
  if (!inFlight_[slot]) return;
  waitForFence(*device_, *fences_[slot], "a shadow trace");
  inFlight_[slot] = false;
  banked_.emplace_back(numberOf_[slot], timestamps_.elapsedMs(slot));
  if (banked_.size() > kMaxBanked) banked_.pop_front();
}

void TraceSubmissions::retireAll() {
  // Oldest first: the order they were submitted in.
  const auto slots = static_cast<std::uint32_t>(fences_.size());
  for (std::uint32_t i = 0; i < slots; ++i) retire((next_ + i) % slots);
}

void TraceSubmissions::retireThrough(std::uint64_t through) {
  // Oldest first, as retireAll(), and only as far as `through`.
  const auto slots = static_cast<std::uint32_t>(fences_.size());
  for (std::uint32_t i = 0; i < slots; ++i) {
    const std::uint32_t slot = (next_ + i) % slots;
    if (inFlight_[slot] && numberOf_[slot] <= through) retire(slot);
  }
}

bool TraceSubmissions::finished(std::uint64_t through) const {
  for (std::size_t slot = 0; slot < fences_.size(); ++slot) {
    if (inFlight_[slot] && numberOf_[slot] <= through &&
        fences_[slot].getStatus() != ::vk::Result::eSuccess) {
      return false;
    }
  }
  return true;
}

double TraceSubmissions::takeGpuMs(std::uint64_t through) {
  retireThrough(through);
  double gpuMs = 0.0;
  std::erase_if(banked_, [&](const std::pair<std::uint64_t, double>& entry) {
    if (entry.first > through) return false;
    gpuMs += entry.second;
    return true;
  });
  return gpuMs;
}

}  // namespace lgh::vk
