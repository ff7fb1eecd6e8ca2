#include "vk/light_path_tracer.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "gl/slots.hpp"
#include "lgh/error.hpp"
#include "vk/acceleration_scene.hpp"
#include "vk/fence_wait.hpp"
#include "vk/hit_tracer.hpp"
#include "vk/shader_module.hpp"
#include "vk/shared_buffer.hpp"
#include "vk/spirv_shaders.hpp"
#include "vk/timestamp_queries.hpp"
#include "vk/trace_recorder.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

using Access = ::vk::AccessFlagBits;
using Stage = ::vk::PipelineStageFlagBits;

// LightPathConstants in glsl/vk/include/light_path_constants.glsl (std430).
struct LightPathPushConstants {
  std::array<float, 4> sceneSphere{};
  std::array<float, 3> sceneMin{};
  float surfaceOffset = 0.0F;
  std::array<float, 3> sceneMax{};
  std::uint32_t sourceCount = 0;
  std::uint32_t pathCount = 0;
  std::uint32_t seed = 0;
  std::uint32_t emissionSlots = 0;
  std::uint32_t bounce = 0;
  std::uint32_t lastBounce = 0;
  std::uint32_t slot = 0;
};
static_assert(sizeof(LightPathPushConstants) == 72, "std430 push constants: 18 scalars");

constexpr std::uint32_t kGroup = 64;          // local_size_x of glsl/vk/gi_*.comp
constexpr std::uint32_t kMaxGroupsX = 65535;  // the Vulkan minimum of work groups along x
constexpr ::vk::DeviceSize kStateBytes = 16;  // vec4 per path
constexpr ::vk::DeviceSize kMinBytes = 16;    // a buffer of 0 bytes cannot be bound
// Timestamps: the start, after the emit kernel, and after each bounce's trace and kernel.
constexpr std::uint32_t kTimestamps = 2 + 2 * kMaxLightPathBounces;

// The set's storage buffers: the GI bindings of include/slots.glsl, as the GL kernels had them.
constexpr std::array<std::uint32_t, 12> kBindings{
    LGH_BIND_GI_RAYS,      LGH_BIND_GI_HITS,       LGH_BIND_GI_VERTICES,
    LGH_BIND_GI_INDICES,   LGH_BIND_GI_GEOMETRIES, LGH_BIND_GI_INSTANCES,
    LGH_BIND_GI_MATERIALS, LGH_BIND_GI_SOURCES,    LGH_BIND_GI_PATHS,
    LGH_BIND_GI_VPLS,      LGH_BIND_GI_LIGHTS,     LGH_BIND_GI_ALBEDO_TEXELS};

::vk::raii::DescriptorSetLayout createSetLayout(const ::vk::raii::Device& device) {
  std::vector<::vk::DescriptorSetLayoutBinding> bindings;
  bindings.reserve(kBindings.size());
  for (const std::uint32_t binding : kBindings) {
    bindings.push_back({.binding = binding,
                        .descriptorType = ::vk::DescriptorType::eStorageBuffer,
                        .descriptorCount = 1,
                        .stageFlags = ::vk::ShaderStageFlagBits::eCompute});
  }
  return {device, ::vk::DescriptorSetLayoutCreateInfo{
                      .bindingCount = static_cast<std::uint32_t>(bindings.size()),
                      .pBindings = bindings.data()}};
}

::vk::raii::PipelineLayout createPipelineLayout(const ::vk::raii::Device& device,
                                                const ::vk::raii::DescriptorSetLayout& set) {
  const ::vk::DescriptorSetLayout layout = *set;
  const ::vk::PushConstantRange constants{.stageFlags = ::vk::ShaderStageFlagBits::eCompute,
                                          .offset = 0,
                                          .size = sizeof(LightPathPushConstants)};
  return {device, ::vk::PipelineLayoutCreateInfo{.setLayoutCount = 1,
                                                 .pSetLayouts = &layout,
                                                 .pushConstantRangeCount = 1,
                                                 .pPushConstantRanges = &constants}};
}

::vk::raii::DescriptorPool createPool(const ::vk::raii::Device& device) {
  const ::vk::DescriptorPoolSize size{
      .type = ::vk::DescriptorType::eStorageBuffer,
      .descriptorCount = static_cast<std::uint32_t>(kBindings.size())};
  return {device, ::vk::DescriptorPoolCreateInfo{
                      .flags = ::vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet,
                      .maxSets = 1,
                      .poolSizeCount = 1,
                      .pPoolSizes = &size}};
}

DeviceBuffer deviceLocal(const VulkanDevice& device, ::vk::DeviceSize size) {
  return {
      device,
      {.size = std::max(size, kMinBytes),
       .usage = ::vk::BufferUsageFlagBits::eStorageBuffer | ::vk::BufferUsageFlagBits::eTransferDst,
       .memory = MemoryKind::DeviceLocal}};
}

// A global barrier: what `from` wrote becomes visible to `to`.
void memoryBarrier(const ::vk::raii::CommandBuffer& commands, ::vk::PipelineStageFlags from,
                   ::vk::AccessFlags written, ::vk::PipelineStageFlags to,
                   ::vk::AccessFlags access) {
  const ::vk::MemoryBarrier barrier{.srcAccessMask = written, .dstAccessMask = access};
  commands.pipelineBarrier(from, to, {}, barrier, nullptr, nullptr);
}

// The VPL buffer handed between GL (the external queue family) and this queue.
void transferVpls(const ::vk::raii::CommandBuffer& commands, ::vk::Buffer vpls,
                  ::vk::PipelineStageFlags from, ::vk::AccessFlags written,
                  ::vk::PipelineStageFlags to, ::vk::AccessFlags access, std::uint32_t fromFamily,
                  std::uint32_t toFamily) {
  const ::vk::BufferMemoryBarrier barrier{.srcAccessMask = written,
                                          .dstAccessMask = access,
                                          .srcQueueFamilyIndex = fromFamily,
                                          .dstQueueFamilyIndex = toFamily,
                                          .buffer = vpls,
                                          .offset = 0,
                                          .size = VK_WHOLE_SIZE};
  commands.pipelineBarrier(from, to, {}, nullptr, barrier, nullptr);
}

void dispatchPaths(const ::vk::raii::CommandBuffer& commands, std::uint32_t paths) {
  const std::uint32_t groups = std::max<std::uint32_t>(1, (paths + kGroup - 1) / kGroup);
  commands.dispatch(std::min(groups, kMaxGroupsX), (groups + kMaxGroupsX - 1) / kMaxGroupsX, 1);
}

LightPathPushConstants constantsOf(const LightPathBatch& batch) {
  return {.sceneSphere = batch.sceneSphere,
          .sceneMin = batch.sceneMin,
          .surfaceOffset = batch.surfaceOffset,
          .sceneMax = batch.sceneMax,
          .sourceCount = batch.sourceCount,
          .pathCount = batch.paths,
          .seed = batch.seed,
          .emissionSlots = batch.emissionSlot ? 1U : 0U};
}

}  // namespace

LightPathTracer::LightPathTracer(const VulkanDevice& device, const HitTracer& hits,
                                 ::vk::ShaderStageFlags traceStages)
    : device_(&device),
      hits_(&hits),
      setLayout_(createSetLayout(device.device())),
      pipelineLayout_(createPipelineLayout(device.device(), setLayout_)),
      pool_(createPool(device.device())),
      sets_(device.device(),
            ::vk::DescriptorSetAllocateInfo{
                .descriptorPool = *pool_, .descriptorSetCount = 1, .pSetLayouts = &*setLayout_}),
      emit_(createComputePipeline(device, *pipelineLayout_, spirv::gi_emit_comp())),
      bounce_(createComputePipeline(device, *pipelineLayout_, spirv::gi_bounce_comp())),
      traceLayout_(createHitTraceLayout(device, traceStages, 1)),
      commandPool_(
          device.device(),
          ::vk::CommandPoolCreateInfo{.flags = ::vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                      .queueFamilyIndex = device.queueFamily()}),
      commands_(device.device(),
                ::vk::CommandBufferAllocateInfo{.commandPool = *commandPool_,
                                                .level = ::vk::CommandBufferLevel::ePrimary,
                                                .commandBufferCount = 1}),
      fence_(device.device(), ::vk::FenceCreateInfo{}),
      periodNs_(device.limits().timestampPeriodNs) {
  if (device.limits().timestamps) {
    queries_.emplace(device.device(),
                     ::vk::QueryPoolCreateInfo{.queryType = ::vk::QueryType::eTimestamp,
                                               .queryCount = kTimestamps});
    stamps_.emplace(device, BufferSpec{.size = kTimestamps * sizeof(std::uint64_t),
                                       .usage = ::vk::BufferUsageFlagBits::eTransferDst,
                                       .memory = MemoryKind::HostVisible});
  }
}

const VplBuffers& LightPathTracer::buffers(std::uint32_t vplCount, Transport transport) {
  const ::vk::DeviceSize bytes = std::max<::vk::DeviceSize>(vplCount, 1) * kVplBytes;
  if (bytes > device_->limits().maxStorageBufferRange) {
    throw Error(ErrorCode::TooLarge,
                fmt::format("{} VPLs need a {} byte buffer; the Vulkan device binds at most {}",
                            vplCount, bytes, device_->limits().maxStorageBufferRange));
  }
  if (transport == Transport::Interop && !device_->capabilities().externalMemoryFd) {
    throw Error(ErrorCode::Unavailable,
                fmt::format("an interop VPL buffer: {} cannot export memory as fds",
                            device_->info().deviceName));
  }
  if (vpls_ && shared_.transport == transport && bytes <= shared_.vpls.size) return shared_;
  retire();  // no submission may still write the old buffer
  const ::vk::DeviceSize size =
      vpls_ && shared_.transport == transport ? std::max(bytes, shared_.vpls.size) : bytes;
  vpls_.reset();
  const std::uint64_t generation = shared_.generation + 1;
  shared_ = VplBuffers{.transport = transport, .generation = generation, .vpls = {}};
  vpls_.emplace(createSharedBuffer(*device_, size, transport));
  shared_.vpls = describeShared(*vpls_, transport);
  spdlog::debug("vulkan: VPL buffer, generation {}: {} bytes ({})", generation, size,
                transport == Transport::Interop ? "interop" : "staging");
  return shared_;
}

SemaphoreFds LightPathTracer::exportSemaphores() {
  if (!device_->capabilities().externalSemaphoreFd) {
    throw Error(ErrorCode::Unavailable,
                fmt::format("{} cannot export semaphores as fds", device_->info().deviceName));
  }
  retire();  // no submission may still wait on or signal the old pair
  semaphores_.emplace(*device_);
  return semaphores_->exportFds();
}

void LightPathTracer::check(const LightPathBatch& batch, bool useSemaphores) const {
  if (batch.paths == 0 || batch.bounces == 0 || batch.bounces > kMaxLightPathBounces ||
      batch.sourceCount == 0) {
    throw Error(ErrorCode::Invalid,
                fmt::format("traceLightPaths: {} paths, {} bounces (1..{}), {} sources",
                            batch.paths, batch.bounces, kMaxLightPathBounces, batch.sourceCount));
  }
  const std::uint64_t slots =
      std::uint64_t{batch.paths} * (batch.bounces + (batch.emissionSlot ? 1U : 0U));
  if (slots > batch.vplCount) {
    throw Error(ErrorCode::Invalid, fmt::format("traceLightPaths: {} slots of paths in {} VPLs",
                                                slots, batch.vplCount));
  }
  if (!vpls_ || std::uint64_t{batch.vplCount} * kVplBytes > shared_.vpls.size) {
    throw Error(ErrorCode::Invalid,
                "traceLightPaths: the VPL buffer does not hold the batch: call vplBuffers() with "
                "its count first");
  }
  if (useSemaphores && !semaphores_) {
    throw Error(ErrorCode::Invalid,
                "traceLightPaths: no semaphores to wait on: call exportLightPathSemaphores()");
  }
  checkHitBatch(batch.paths, device_->limits().maxStorageBufferRange);
}

void LightPathTracer::prepare(const LightPathScene& surfaces, const LightPathBatch& batch) {
  if (!surfaces_ || surfaces_->id() != surfaces.id) {
    surfaces_.reset();
    surfaces_.emplace(*device_, surfaces);
  }
  if (!working_ || working_->paths < batch.paths) {
    working_.reset();
    working_.emplace(Working{.paths = batch.paths,
                             .rays = deviceLocal(*device_, batch.paths * kHitRayBytes),
                             .hits = deviceLocal(*device_, batch.paths * kHitRecordBytes),
                             .states = deviceLocal(*device_, batch.paths * kStateBytes)});
  }
  const ::vk::DeviceSize sourceBytes = std::max<::vk::DeviceSize>(batch.sources.size(), kMinBytes);
  const ::vk::DeviceSize lightBytes = std::max<::vk::DeviceSize>(batch.lights.size(), kMinBytes);
  if (!inputs_ || inputs_->sourceBytes < sourceBytes || inputs_->lightBytes < lightBytes) {
    const ::vk::DeviceSize sources = std::max(sourceBytes, inputs_ ? inputs_->sourceBytes : 0);
    const ::vk::DeviceSize lights = std::max(lightBytes, inputs_ ? inputs_->lightBytes : 0);
    inputs_.reset();
    inputs_.emplace(
        Inputs{.sourceBytes = sources,
               .lightBytes = lights,
               .staging = DeviceBuffer(*device_, {.size = sources + lights,
                                                  .usage = ::vk::BufferUsageFlagBits::eTransferSrc,
                                                  .memory = MemoryKind::HostVisible}),
               .sources = deviceLocal(*device_, sources),
               .lights = deviceLocal(*device_, lights)});
  }
  if (!batch.sources.empty()) {
    std::memcpy(inputs_->staging.mapped(), batch.sources.data(), batch.sources.size());
  }
  if (!batch.lights.empty()) {
    std::memcpy(inputs_->staging.mapped() + inputs_->sourceBytes, batch.lights.data(),
                batch.lights.size());
  }
}

void LightPathTracer::writeSets(const AccelerationScene& scene) const {
  const auto surfaces = surfaces_->buffers();
  // In kBindings' order.
  const std::array<::vk::Buffer, kBindings.size()> buffers{working_->rays.handle(),
                                                           working_->hits.handle(),
                                                           surfaces[0],
                                                           surfaces[1],
                                                           surfaces[2],
                                                           surfaces[3],
                                                           surfaces[4],
                                                           inputs_->sources.handle(),
                                                           working_->states.handle(),
                                                           vpls_->handle(),
                                                           inputs_->lights.handle(),
                                                           surfaces[5]};
  std::array<::vk::DescriptorBufferInfo, kBindings.size()> infos{};
  std::array<::vk::WriteDescriptorSet, kBindings.size()> writes{};
  const ::vk::DescriptorSet set = *sets_[0];
  for (std::size_t i = 0; i < kBindings.size(); ++i) {
    infos[i] =
        ::vk::DescriptorBufferInfo{.buffer = buffers[i], .offset = 0, .range = VK_WHOLE_SIZE};
    writes[i] = ::vk::WriteDescriptorSet{.dstSet = set,
                                         .dstBinding = kBindings[i],
                                         .descriptorCount = 1,
                                         .descriptorType = ::vk::DescriptorType::eStorageBuffer,
                                         .pBufferInfo = &infos[i]};
  }
  device_->device().updateDescriptorSets(writes, nullptr);
  const std::array<::vk::Buffer, 2> traced{working_->rays.handle(), working_->hits.handle()};
  traceLayout_.write(0, scene.topLevel(), traced);
}

void LightPathTracer::record(const TraceRecorder& recorder, const LightPathBatch& batch) const {
  const ::vk::raii::CommandBuffer& commands = commands_.front();
  const ::vk::PipelineStageFlags kernels = Stage::eComputeShader | recorder.stage();
  const ::vk::AccessFlags shaderAccess = Access::eShaderRead | Access::eShaderWrite;
  const bool interop = shared_.transport == Transport::Interop;
  const auto stamp = [&](std::uint32_t index, Stage stage) {
    if (queries_) commands.writeTimestamp(stage, **queries_, index);
  };
  commands.begin({.flags = ::vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  if (queries_) commands.resetQueryPool(**queries_, 0, kTimestamps);
  stamp(0, Stage::eTopOfPipe);
  if (interop) {
    // Acquire: GL is done reading last frame's VPLs (its semaphore signal or glFinish).
    transferVpls(commands, vpls_->handle(), Stage::eTopOfPipe, {},
                 Stage::eTransfer | Stage::eComputeShader,
                 Access::eTransferWrite | Access::eShaderWrite, VK_QUEUE_FAMILY_EXTERNAL,
                 device_->queueFamily());
  }
  if (!batch.sources.empty()) {
    commands.copyBuffer(
        inputs_->staging.handle(), inputs_->sources.handle(),
        ::vk::BufferCopy{.srcOffset = 0, .dstOffset = 0, .size = batch.sources.size()});
  }
  if (!batch.lights.empty()) {
    commands.copyBuffer(
        inputs_->staging.handle(), inputs_->lights.handle(),
        ::vk::BufferCopy{
            .srcOffset = inputs_->sourceBytes, .dstOffset = 0, .size = batch.lights.size()});
  }
  const ::vk::DeviceSize written =
      ::vk::DeviceSize{batch.paths} * (batch.bounces + (batch.emissionSlot ? 1U : 0U)) * kVplBytes;
  const ::vk::DeviceSize total = ::vk::DeviceSize{batch.vplCount} * kVplBytes;
  if (total > written) commands.fillBuffer(vpls_->handle(), written, total - written, 0);
  // The uploads, the clear and the scene (built or uploaded by earlier submissions).
  memoryBarrier(commands, Stage::eTransfer | Stage::eAccelerationStructureBuildKHR,
                Access::eTransferWrite | Access::eAccelerationStructureWriteKHR, kernels,
                shaderAccess | Access::eAccelerationStructureReadKHR);

  LightPathPushConstants constants = constantsOf(batch);
  const auto runKernel = [&](const ::vk::raii::Pipeline& pipeline) {
    commands.bindPipeline(::vk::PipelineBindPoint::eCompute, *pipeline);
    commands.bindDescriptorSets(::vk::PipelineBindPoint::eCompute, *pipelineLayout_, 0, *sets_[0],
                                nullptr);
    commands.pushConstants<LightPathPushConstants>(
        *pipelineLayout_, ::vk::ShaderStageFlagBits::eCompute, 0, constants);
    dispatchPaths(commands, batch.paths);
  };
  runKernel(emit_);
  stamp(1, Stage::eBottomOfPipe);
  const HitBatchShape shape{.rays = batch.paths, .query = HitQuery::Closest};
  const HitPushConstants hitConstants = hitBatchConstants(shape);
  for (std::uint32_t bounce = 1; bounce <= batch.bounces; ++bounce) {
    memoryBarrier(commands, kernels, Access::eShaderWrite, kernels, shaderAccess);
    recorder.record(commands, traceLayout_.set(0), constantBytes(hitConstants),
                    hitBatchLaunch(shape));
    stamp(2 * bounce, Stage::eBottomOfPipe);
    memoryBarrier(commands, kernels, Access::eShaderWrite, kernels, shaderAccess);
    constants.bounce = bounce;
    constants.lastBounce = bounce == batch.bounces ? 1U : 0U;
    constants.slot = bounce - 1 + (batch.emissionSlot ? 1U : 0U);
    runKernel(bounce_);
    stamp(2 * bounce + 1, Stage::eBottomOfPipe);
  }
  if (queries_) copyQueriesToHost(commands, **queries_, 0, 2 + 2 * batch.bounces, *stamps_, 0);
  if (interop) {
    // Release to GL, which reads after the vkDone semaphore (or once trace() has returned).
    transferVpls(commands, vpls_->handle(), kernels | Stage::eTransfer,
                 Access::eShaderWrite | Access::eTransferWrite, Stage::eBottomOfPipe, {},
                 device_->queueFamily(), VK_QUEUE_FAMILY_EXTERNAL);
  } else {
    memoryBarrier(commands, kernels | Stage::eTransfer,
                  Access::eShaderWrite | Access::eTransferWrite, Stage::eHost, Access::eHostRead);
  }
  commands.end();
}

void LightPathTracer::submit(bool useSemaphores) {
  const ::vk::Semaphore wait = useSemaphores ? semaphores_->glDone() : ::vk::Semaphore{};
  const ::vk::Semaphore signal = useSemaphores ? semaphores_->vkDone() : ::vk::Semaphore{};
  device_->submit(*commands_.front(), *fence_, wait, Stage::eAllCommands, signal);
  inFlight_ = true;
  ++submitted_;
}

void LightPathTracer::trace(const AccelerationScene& scene, TracePath path,
                            const LightPathScene& surfaces, const LightPathBatch& batch,
                            bool useSemaphores) {
  const TraceRecorder& recorder = hits_->recorder(path);
  check(batch, useSemaphores);
  retire();  // the previous frame's submission may still read the inputs and the sets
  prepare(surfaces, batch);
  writeSets(scene);
  device_->device().resetFences(*fence_);
  commands_.front().reset();
  record(recorder, batch);
  submit(useSemaphores);
  inFlightBounces_ = batch.bounces;
  if (!useSemaphores) retire();
}

void LightPathTracer::retire() {
  if (!inFlight_) return;
  waitForFence(*device_, *fence_, "the light paths");
  inFlight_ = false;
  LightPathTimings& timings = banked_.emplace_back(submitted_, LightPathTimings{}).second;
  if (banked_.size() > kMaxBanked) banked_.pop_front();
  timings.traced = true;
  if (!queries_) return;
  const std::uint32_t count = 2 + 2 * inFlightBounces_;
  std::vector<std::uint64_t> ticks(count);  // after the fence: the queue's copy is there
  std::memcpy(ticks.data(), stamps_->mapped(), count * sizeof(std::uint64_t));
  const auto ms = [&](std::uint32_t from, std::uint32_t to) {
    return ticks[to] < ticks[from]
               ? 0.0
               : static_cast<double>(ticks[to] - ticks[from]) * periodNs_ * 1e-6;
  };
  timings.totalMs = ms(0, count - 1);
  timings.emitMs = ms(0, 1);
  for (std::uint32_t bounce = 1; bounce <= inFlightBounces_; ++bounce) {
    timings.raysMs += ms(2 * bounce - 1, 2 * bounce);
    timings.bounceMs[bounce - 1] = ms(2 * bounce, 2 * bounce + 1);
  }
}

LightPathTimings LightPathTracer::collectTimings(std::uint64_t through) {
  if (inFlight_ && submitted_ <= through) retire();
  LightPathTimings sum;
  while (!banked_.empty() && banked_.front().first <= through) {
    const LightPathTimings& timings = banked_.front().second;
    sum.traced = true;
    sum.totalMs += timings.totalMs;
    sum.emitMs += timings.emitMs;
    sum.raysMs += timings.raysMs;
    for (std::size_t b = 0; b < sum.bounceMs.size(); ++b) sum.bounceMs[b] += timings.bounceMs[b];
    banked_.pop_front();
  }
  return sum;
}

}  // namespace lgh::vk
