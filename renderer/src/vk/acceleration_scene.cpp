#include "vk/acceleration_scene.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/stopwatch.hpp"
#include "scene/scene.hpp"
#include "vk/bottom_levels.hpp"
#include "vk/scene_geometry.hpp"
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

}  // namespace

std::unique_ptr<AccelerationScene> AccelerationScene::build(
    std::shared_ptr<const VulkanDevice> device, const Scene& scene) {
  const Stopwatch wallClock;
  const PackedGeometry geometry = packGeometry(scene);
  BottomLevels bottom = buildBottomLevels(*device, geometry);
  TopLevel top = buildTopLevel(*device, tlasInstances(scene, meshAddresses(bottom)));
  std::unique_ptr<AccelerationScene> built(new AccelerationScene(
      std::move(device), std::move(bottom.structures), std::move(top.structure)));
  built->buildGpuMs_ = bottom.buildGpuMs + top.buildGpuMs;
  built->triangleCount_ = geometry.triangleCount;
  spdlog::info(
      "vulkan: scene '{}': {} triangles in {} bottom levels, {} instances: {:.1f} MB, GPU "
      "{:.2f} ms, wall {:.1f} ms{}",
      scene.name, geometry.triangleCount, built->bottomLevels_.size(), scene.instances.size(),
      static_cast<double>(built->gpuBytes()) / 1e6, built->buildGpuMs_, wallClock.elapsedMs(),
      geometry.droppedTriangles > 0
          ? fmt::format(" ({} triangles with indices out of range dropped)",
                        geometry.droppedTriangles)
          : std::string());
  return built;
}

AccelerationScene::AccelerationScene(std::shared_ptr<const VulkanDevice> device,
                                     std::vector<AccelerationStructure> bottomLevels,
                                     AccelerationStructure topLevel)
    : device_(std::move(device)),
      bottomLevels_(std::move(bottomLevels)),
      topLevel_(std::move(topLevel)) {}

AccelerationScene::~AccelerationScene() { device_->waitIdleNoThrow(); }

std::size_t AccelerationScene::gpuBytes() const {
  ::vk::DeviceSize bytes = topLevel_.memoryBytes();
  for (const AccelerationStructure& structure : bottomLevels_) bytes += structure.memoryBytes();
  return static_cast<std::size_t>(bytes);
}

}  // namespace lgh::vk
