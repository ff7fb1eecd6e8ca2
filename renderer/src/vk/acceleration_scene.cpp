#include "vk/acceleration_scene.hpp"

#include <algorithm>
#include <new>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/stopwatch.hpp"
#include "scene/scene.hpp"
#include "vk/bottom_levels.hpp"
#include "vk/deferred_release.hpp"
#include "vk/one_time_commands.hpp"
#include "vk/scene_geometry.hpp"
#include "vk/timestamp_queries.hpp"
#include "vk/tlas_instances.hpp"
#include "vk/top_level.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

std::vector<std::optional<::vk::DeviceAddress>> meshAddresses(const BottomLevels& levels) {
  std::vector<std::optional<::vk::DeviceAddress>> addresses;
  addresses.reserve(levels.structureOfMesh.size());
  for (const std::optional<std::size_t>& structure : levels.structureOfMesh) {
    addresses.push_back(structure ? std::optional(levels.structures[*structure].address())
                                  : std::nullopt);
  }
  return addresses;
}

// A large scene: compacted bottom levels (two submissions), then the top level (a third).
std::pair<BottomLevels, AccelerationStructure> buildCompacted(const VulkanDevice& device,
                                                              OneTimeCommands& oneTime,
                                                              const Scene& scene,
                                                              BottomLevelBuilds& bottomBuilds,
                                                              double& buildGpuMs) {
  BottomLevels bottom = bottomBuilds.buildCompacted();
  const auto instances = tlasInstances(scene, meshAddresses(bottom));
  TopLevelBuild topBuild(device, oneTime, static_cast<std::uint32_t>(instances.size()));
  double topGpuMs = 0.0;
  AccelerationStructure top = topBuild.build(instances, topGpuMs);
  buildGpuMs = bottom.buildGpuMs + topGpuMs;
  return {std::move(bottom), std::move(top)};
}

// A small scene: every structure in one buffer, built in one submission that nothing waits for
// here; its GPU time goes to `buildGpuMs` when it is retired (OneTimeCommands).
std::pair<BottomLevels, AccelerationStructure> buildTogether(
    const VulkanDevice& device, OneTimeCommands& oneTime, const Scene& scene,
    BottomLevelBuilds& bottomBuilds, const std::shared_ptr<double>& buildGpuMs, double& submitMs) {
  // Sized for every instance: those of meshes without triangles are left out of the build.
  TopLevelBuild topBuild(device, oneTime, static_cast<std::uint32_t>(scene.instances.size()));
  const ::vk::DeviceSize topOffset =
      alignUp(bottomBuilds.storageBytes(), AccelerationStructure::kOffsetAlignment);
  const std::shared_ptr<const DeviceBuffer> storage =
      device.structureStorage().take(topOffset + topBuild.storageBytes());
  const ::vk::DeviceSize topScratch =
      alignUp(bottomBuilds.scratchBytes(), device.limits().scratchAlignment);
  const DeviceBuffer& scratch = oneTime.transientBuffers().get(
      device, accelerationScratch(device, topScratch + topBuild.scratchBytes()));
  BottomLevels bottom = bottomBuilds.place(storage, 0);
  AccelerationStructure top = topBuild.place(storage, topOffset);
  const auto instances = tlasInstances(scene, meshAddresses(bottom));
  const TimestampQueries& timestamps = oneTime.timestamps();
  const Stopwatch submission;
  oneTime.submit(
      device,
      [&](const ::vk::raii::CommandBuffer& commands) {
        bottomBuilds.recordUpload(commands);
        timestamps.begin(commands, 0);
        bottomBuilds.recordBuilds(commands, scratch.address());
        topBuild.record(commands, instances, scratch.address() + topScratch);
        timestamps.end(commands, 0);
      },
      [buildGpuMs, &timestamps] { *buildGpuMs = timestamps.elapsedMs(0); });
  submitMs = submission.elapsedMs();
  return {std::move(bottom), std::move(top)};
}

}  // namespace

std::unique_ptr<AccelerationScene> AccelerationScene::build(
    std::shared_ptr<const VulkanDevice> device, const Scene& scene) {
  OneTimeCommands& frames = device->oneTimeCommands();
  return build(std::move(device), scene, frames);
}

std::unique_ptr<AccelerationScene> AccelerationScene::build(
    std::shared_ptr<const VulkanDevice> device, const Scene& scene, OneTimeCommands& oneTime) {
  // Where the wall time goes (the log line): packing, the turn (waiting for another thread's
  // build and the previous build's GPU work), the geometry's buffers, the rest of the
  // allocations and recording, and the submission (waited for only on the compacted path).
  const Stopwatch wallClock;
  // Packing is the CPU's alone: prefetch threads pack side by side.
  const PackedGeometry geometry = packGeometry(scene);
  const double packMs = wallClock.elapsedMs();
  // Builds with the same one-time commands share their transient buffers: one at a time (the
  // render thread's and the prefetch threads' side by side).
  const std::unique_lock<std::mutex> oneBuild = oneTime.buildLock();
  // The previous build may still read the transient buffers that this one fills.
  oneTime.retire(*device);
  device->deferredRelease().collect();
  const double turnMs = wallClock.elapsedMs() - packMs;
  BottomLevelBuilds bottomBuilds(*device, oneTime, geometry);
  const double prepareMs = wallClock.elapsedMs() - packMs - turnMs;
  auto buildGpuMs = std::make_shared<double>(-1.0);
  double submitMs = -1.0;  // the compacted path's several submissions are not split out
  const bool compacted = bottomBuilds.worthCompacting();
  double compactedGpuMs = 0.0;
  auto built = compacted
                   ? buildCompacted(*device, oneTime, scene, bottomBuilds, compactedGpuMs)
                   : buildTogether(*device, oneTime, scene, bottomBuilds, buildGpuMs, submitMs);
  if (compacted) *buildGpuMs = compactedGpuMs;
  std::unique_ptr<AccelerationScene> result(new AccelerationScene(
      std::move(device), std::move(built.first.structures), std::move(built.second)));
  result->buildGpuMs_ = std::move(buildGpuMs);
  result->oneTime_ = &oneTime;
  result->triangleCount_ = geometry.triangleCount;
  const double wallMs = wallClock.elapsedMs();
  spdlog::info(
      "vulkan: scene '{}': {} triangles in {} bottom levels, {} instances: {:.1f} MB, wall "
      "{:.2f} ms (pack {:.2f}, turn {:.2f}, geometry buffers {:.2f}, {}){}",
      scene.name, geometry.triangleCount, result->bottomLevels_.size(), scene.instances.size(),
      static_cast<double>(result->gpuBytes()) / 1e6, wallMs, packMs, turnMs, prepareMs,
      compacted ? fmt::format("compacted builds {:.2f}, GPU {:.2f} ms",
                              wallMs - packMs - turnMs - prepareMs, *result->buildGpuMs_)
                : fmt::format("build buffers {:.2f}, submit {:.2f}; not waited for",
                              wallMs - packMs - turnMs - prepareMs - submitMs, submitMs),
      geometry.droppedTriangles > 0
          ? fmt::format(" ({} triangles with indices out of range dropped)",
                        geometry.droppedTriangles)
          : std::string());
  return result;
}

std::function<double()> AccelerationScene::buildGpuMsReader() const {
  return [device = device_, gpuMs = buildGpuMs_, oneTime = oneTime_] {
    if (*gpuMs < 0.0) oneTime->retire(*device);
    return std::max(*gpuMs, 0.0);
  };
}

AccelerationScene::AccelerationScene(std::shared_ptr<const VulkanDevice> device,
                                     std::vector<AccelerationStructure> bottomLevels,
                                     AccelerationStructure topLevel)
    : device_(std::move(device)),
      bottomLevels_(std::move(bottomLevels)),
      topLevel_(std::move(topLevel)) {}

AccelerationScene::~AccelerationScene() {
  struct Structures {
    std::vector<AccelerationStructure> bottomLevels;
    AccelerationStructure topLevel;
  };
  try {
    device_->deferredRelease().release(
        std::make_shared<Structures>(Structures{std::move(bottomLevels_), std::move(topLevel_)}));
  } catch (const std::bad_alloc&) {
    device_->waitIdleNoThrow();  // the members, whatever was not moved, go right after this
  }
}

std::size_t AccelerationScene::gpuBytes() const {
  ::vk::DeviceSize bytes = topLevel_.memoryBytes();
  for (const AccelerationStructure& structure : bottomLevels_) bytes += structure.memoryBytes();
  return static_cast<std::size_t>(bytes);
}

}  // namespace lgh::vk
