#include "vk/timestamp_queries.hpp"

#include <array>
#include <cstring>

#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

constexpr ::vk::DeviceSize kPairBytes = 2 * sizeof(std::uint64_t);

}  // namespace

void copyQueriesToHost(const ::vk::raii::CommandBuffer& commands, ::vk::QueryPool pool,
                       std::uint32_t first, std::uint32_t count, const DeviceBuffer& results,
                       ::vk::DeviceSize offset) {
  commands.copyQueryPoolResults(pool, first, count, results.handle(), results.offset() + offset,
                                sizeof(std::uint64_t),
                                ::vk::QueryResultFlagBits::e64 | ::vk::QueryResultFlagBits::eWait);
  const ::vk::MemoryBarrier toHost{.srcAccessMask = ::vk::AccessFlagBits::eTransferWrite,
                                   .dstAccessMask = ::vk::AccessFlagBits::eHostRead};
  commands.pipelineBarrier(::vk::PipelineStageFlagBits::eTransfer,
                           ::vk::PipelineStageFlagBits::eHost, {}, toHost, {}, {});
}

TimestampQueries::TimestampQueries(const VulkanDevice& device, std::uint32_t pairs)
    : periodNs_(device.limits().timestampPeriodNs) {
  if (!device.limits().timestamps) return;
  pool_.emplace(device.device(), ::vk::QueryPoolCreateInfo{.queryType = ::vk::QueryType::eTimestamp,
                                                           .queryCount = 2 * pairs});
  results_.emplace(device, BufferSpec{.size = pairs * kPairBytes,
                                      .usage = ::vk::BufferUsageFlagBits::eTransferDst,
                                      .memory = MemoryKind::HostVisible});
  std::memset(results_->mapped(), 0, static_cast<std::size_t>(pairs * kPairBytes));
}

std::uint64_t* TimestampQueries::ticks(std::uint32_t pair) const {
  return reinterpret_cast<std::uint64_t*>(results_->mapped() + pair * kPairBytes);
}

void TimestampQueries::begin(const ::vk::raii::CommandBuffer& commands, std::uint32_t pair) const {
  if (!pool_) return;
  std::memset(ticks(pair), 0, kPairBytes);
  commands.resetQueryPool(**pool_, 2 * pair, 2);
  commands.writeTimestamp(::vk::PipelineStageFlagBits::eTopOfPipe, **pool_, 2 * pair);
}

void TimestampQueries::end(const ::vk::raii::CommandBuffer& commands, std::uint32_t pair) const {
  if (!pool_) return;
  commands.writeTimestamp(::vk::PipelineStageFlagBits::eBottomOfPipe, **pool_, 2 * pair + 1);
  copyQueriesToHost(commands, **pool_, 2 * pair, 2, *results_, pair * kPairBytes);
}

double TimestampQueries::elapsedMs(std::uint32_t pair) const {
  if (!pool_) return 0.0;
  std::array<std::uint64_t, 2> values{};
  std::memcpy(values.data(), ticks(pair), kPairBytes);
  if (values[0] == 0 || values[1] < values[0]) return 0.0;
  return static_cast<double>(values[1] - values[0]) * periodNs_ * 1e-6;
}

}  // namespace lgh::vk
