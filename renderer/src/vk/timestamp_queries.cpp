#include "vk/timestamp_queries.hpp"

#include "vk/vulkan_device.hpp"

namespace lgh::vk {

TimestampQueries::TimestampQueries(const VulkanDevice& device, std::uint32_t pairs)
    : periodNs_(device.limits().timestampPeriodNs) {
  if (!device.limits().timestamps) return;
  pool_.emplace(device.device(), ::vk::QueryPoolCreateInfo{.queryType = ::vk::QueryType::eTimestamp,
                                                           .queryCount = 2 * pairs});
}

void TimestampQueries::begin(const ::vk::raii::CommandBuffer& commands, std::uint32_t pair) const {
  if (!pool_) return;
  commands.resetQueryPool(**pool_, 2 * pair, 2);
  commands.writeTimestamp(::vk::PipelineStageFlagBits::eTopOfPipe, **pool_, 2 * pair);
}

void TimestampQueries::end(const ::vk::raii::CommandBuffer& commands, std::uint32_t pair) const {
  if (!pool_) return;
  commands.writeTimestamp(::vk::PipelineStageFlagBits::eBottomOfPipe, **pool_, 2 * pair + 1);
}

double TimestampQueries::elapsedMs(std::uint32_t pair) const {
  if (!pool_) return 0.0;
  const auto [result, ticks] =
      pool_->getResults<std::uint64_t>(2 * pair, 2, 2 * sizeof(std::uint64_t),
                                       sizeof(std::uint64_t), ::vk::QueryResultFlagBits::e64);
  if (result != ::vk::Result::eSuccess || ticks[1] < ticks[0]) return 0.0;
  return static_cast<double>(ticks[1] - ticks[0]) * periodNs_ * 1e-6;
}

}  // namespace lgh::vk
