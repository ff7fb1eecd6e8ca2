#include "vk/bottom_levels.hpp"

#include <cstring>

#include <glm/vec3.hpp>

#include "vk/one_time_commands.hpp"
#include "vk/scene_geometry.hpp"
#include "vk/timestamp_queries.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

using BuildFlag = ::vk::BuildAccelerationStructureFlagBitsKHR;
constexpr ::vk::DeviceSize kPositionBytes = sizeof(glm::vec3);
constexpr ::vk::DeviceSize kIndexBytes = sizeof(std::uint32_t);
// Compaction halves a bottom level's memory or so, but costs a round trip to the GPU (the
// compacted sizes are read back before the copies) and a second allocation per mesh: worth it
// for large scenes, not for the small ones a thumbnail batch loads by the dozen.
constexpr ::vk::DeviceSize kCompactFromBytes = 8ULL << 20;

void memoryBarrier(const ::vk::raii::CommandBuffer& commands, ::vk::PipelineStageFlags from,
                   ::vk::AccessFlags written, ::vk::PipelineStageFlags to, ::vk::AccessFlags read) {
  commands.pipelineBarrier(from, to, {},
                           ::vk::MemoryBarrier{.srcAccessMask = written, .dstAccessMask = read},
                           nullptr, nullptr);
}

// The positions, then the indices, in one device-local buffer, filled through a staging buffer.
class GeometryUpload {
 public:
  GeometryUpload(const VulkanDevice& device, const PackedGeometry& geometry)
      : indexOffset_(geometry.positions.size() * kPositionBytes),
        staging_(device, {.size = indexOffset_ + geometry.indices.size() * kIndexBytes,
                          .usage = ::vk::BufferUsageFlagBits::eTransferSrc,
                          .memory = MemoryKind::HostVisible}),
        buffer_(device,
                {.size = staging_.size(),
                 .usage = ::vk::BufferUsageFlagBits::eTransferDst |
                          ::vk::BufferUsageFlagBits::eAccelerationStructureBuildInputReadOnlyKHR,
                 .memory = MemoryKind::DeviceLocal,
                 .deviceAddress = true}) {
    std::memcpy(staging_.mapped(), geometry.positions.data(), indexOffset_);
    std::memcpy(staging_.mapped() + indexOffset_, geometry.indices.data(),
                geometry.indices.size() * kIndexBytes);
  }

  void record(const ::vk::raii::CommandBuffer& commands) const {
    commands.copyBuffer(staging_.handle(), buffer_.handle(),
                        ::vk::BufferCopy{.size = staging_.size()});
    // Builds read their vertices and indices as shader reads in the build stage.
    memoryBarrier(commands, ::vk::PipelineStageFlagBits::eTransfer,
                  ::vk::AccessFlagBits::eTransferWrite,
                  ::vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR,
                  ::vk::AccessFlagBits::eShaderRead);
  }
  ::vk::DeviceAddress positions() const { return buffer_.address(); }
  ::vk::DeviceAddress indices() const { return buffer_.address() + indexOffset_; }

 private:
  ::vk::DeviceSize indexOffset_;
  DeviceBuffer staging_;
  DeviceBuffer buffer_;
};

::vk::AccelerationStructureGeometryKHR triangles(const PackedPrimitive& primitive,
                                                 const GeometryUpload& upload) {
  const ::vk::AccelerationStructureGeometryTrianglesDataKHR data{
      .vertexFormat = ::vk::Format::eR32G32B32Sfloat,
      .vertexData = upload.positions() + primitive.firstVertex * kPositionBytes,
      .vertexStride = kPositionBytes,
      .maxVertex = primitive.vertexCount - 1,
      .indexType = ::vk::IndexType::eUint32,
      .indexData = upload.indices() + primitive.firstIndex * kIndexBytes};
  return {.geometryType = ::vk::GeometryTypeKHR::eTriangles,
          .geometry = data,
          .flags = ::vk::GeometryFlagBitsKHR::eOpaque};
}

// One mesh's build: its geometries, their triangle counts, and where it goes.
struct MeshBuild {
  std::vector<::vk::AccelerationStructureGeometryKHR> geometries;
  std::vector<::vk::AccelerationStructureBuildRangeInfoKHR> ranges;
  ::vk::DeviceSize scratchOffset = 0;
  ::vk::DeviceSize bytes = 0;
  std::optional<AccelerationStructure> uncompacted;

  ::vk::AccelerationStructureBuildGeometryInfoKHR info(::vk::DeviceAddress scratch = 0) const {
    return {.type = ::vk::AccelerationStructureTypeKHR::eBottomLevel,
            .flags = BuildFlag::ePreferFastTrace | BuildFlag::eAllowCompaction,
            .mode = ::vk::BuildAccelerationStructureModeKHR::eBuild,
            .dstAccelerationStructure = uncompacted ? uncompacted->handle() : nullptr,
            .geometryCount = static_cast<std::uint32_t>(geometries.size()),
            .pGeometries = geometries.data(),
            .scratchData = scratch + scratchOffset};
  }
};

MeshBuild prepareMesh(const VulkanDevice& device, const PackedMesh& mesh,
                      const GeometryUpload& upload, ::vk::DeviceSize& scratchBytes) {
  MeshBuild build;
  std::vector<std::uint32_t> counts;
  for (const PackedPrimitive& primitive : mesh.primitives) {
    build.geometries.push_back(triangles(primitive, upload));
    build.ranges.push_back({.primitiveCount = primitive.triangleCount});
    counts.push_back(primitive.triangleCount);
  }
  const auto sizes = device.device().getAccelerationStructureBuildSizesKHR(
      ::vk::AccelerationStructureBuildTypeKHR::eDevice, build.info(), counts);
  build.uncompacted.emplace(device, ::vk::AccelerationStructureTypeKHR::eBottomLevel,
                            sizes.accelerationStructureSize);
  build.bytes = sizes.accelerationStructureSize;
  build.scratchOffset = scratchBytes;
  scratchBytes += alignUp(sizes.buildScratchSize, device.limits().scratchAlignment);
  return build;
}

void recordBuilds(const ::vk::raii::CommandBuffer& commands, const std::vector<MeshBuild>& builds,
                  ::vk::DeviceAddress scratch) {
  std::vector<::vk::AccelerationStructureBuildGeometryInfoKHR> infos;
  std::vector<const ::vk::AccelerationStructureBuildRangeInfoKHR*> ranges;
  infos.reserve(builds.size());
  ranges.reserve(builds.size());
  for (const MeshBuild& build : builds) {
    infos.push_back(build.info(scratch));
    ranges.push_back(build.ranges.data());
  }
  commands.buildAccelerationStructuresKHR(infos, ranges);
}

// The builds' compacted sizes, through a query written once they have finished.
void recordSizeQuery(const ::vk::raii::CommandBuffer& commands,
                     const std::vector<MeshBuild>& builds, const ::vk::raii::QueryPool& sizes) {
  std::vector<::vk::AccelerationStructureKHR> handles;
  handles.reserve(builds.size());
  for (const MeshBuild& build : builds) handles.push_back(build.uncompacted->handle());
  commands.resetQueryPool(*sizes, 0, static_cast<std::uint32_t>(handles.size()));
  memoryBarrier(commands, ::vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR,
                ::vk::AccessFlagBits::eAccelerationStructureWriteKHR,
                ::vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR,
                ::vk::AccessFlagBits::eAccelerationStructureReadKHR);
  commands.writeAccelerationStructuresPropertiesKHR(
      handles, ::vk::QueryType::eAccelerationStructureCompactedSizeKHR, *sizes, 0);
}

std::vector<AccelerationStructure> compact(const VulkanDevice& device,
                                           const std::vector<MeshBuild>& builds,
                                           const ::vk::raii::QueryPool& sizeQueries,
                                           const TimestampQueries& timestamps) {
  const auto count = static_cast<std::uint32_t>(builds.size());
  const std::vector<::vk::DeviceSize> sizes =
      sizeQueries
          .getResults<::vk::DeviceSize>(
              0, count, count * sizeof(::vk::DeviceSize), sizeof(::vk::DeviceSize),
              ::vk::QueryResultFlagBits::e64 | ::vk::QueryResultFlagBits::eWait)
          .second;
  std::vector<AccelerationStructure> compacted;
  compacted.reserve(builds.size());
  for (const ::vk::DeviceSize size : sizes) {
    compacted.emplace_back(device, ::vk::AccelerationStructureTypeKHR::eBottomLevel, size);
  }
  submitAndWait(device, [&](const ::vk::raii::CommandBuffer& commands) {
    timestamps.begin(commands, 1);
    for (std::size_t i = 0; i < builds.size(); ++i) {
      commands.copyAccelerationStructureKHR(
          {.src = builds[i].uncompacted->handle(),
           .dst = compacted[i].handle(),
           .mode = ::vk::CopyAccelerationStructureModeKHR::eCompact});
    }
    timestamps.end(commands, 1);
  });
  return compacted;
}

}  // namespace

BottomLevels buildBottomLevels(const VulkanDevice& device, const PackedGeometry& geometry) {
  BottomLevels levels;
  levels.structureOfMesh.resize(geometry.meshes.size());
  if (geometry.triangleCount == 0) return levels;
  const GeometryUpload upload(device, geometry);
  std::vector<MeshBuild> builds;
  ::vk::DeviceSize scratchBytes = 0;
  for (std::size_t m = 0; m < geometry.meshes.size(); ++m) {
    if (geometry.meshes[m].empty()) continue;
    levels.structureOfMesh[m] = builds.size();
    builds.push_back(prepareMesh(device, geometry.meshes[m], upload, scratchBytes));
  }
  ::vk::DeviceSize uncompactedBytes = 0;
  for (const MeshBuild& build : builds) uncompactedBytes += build.bytes;
  const bool compacted = uncompactedBytes >= kCompactFromBytes;
  const DeviceBuffer scratch(device, {.size = scratchBytes,
                                      .usage = ::vk::BufferUsageFlagBits::eStorageBuffer,
                                      .memory = MemoryKind::DeviceLocal,
                                      .deviceAddress = true,
                                      .addressAlignment = device.limits().scratchAlignment});
  const ::vk::raii::QueryPool sizeQueries(
      device.device(), ::vk::QueryPoolCreateInfo{
                           .queryType = ::vk::QueryType::eAccelerationStructureCompactedSizeKHR,
                           .queryCount = static_cast<std::uint32_t>(builds.size())});
  const TimestampQueries timestamps(device, 2);
  submitAndWait(device, [&](const ::vk::raii::CommandBuffer& commands) {
    upload.record(commands);
    timestamps.begin(commands, 0);
    recordBuilds(commands, builds, scratch.address());
    if (compacted) recordSizeQuery(commands, builds, sizeQueries);
    timestamps.end(commands, 0);
  });
  if (!compacted) {
    for (MeshBuild& build : builds) levels.structures.push_back(std::move(*build.uncompacted));
    levels.buildGpuMs = timestamps.elapsedMs(0);
    return levels;
  }
  levels.structures = compact(device, builds, sizeQueries, timestamps);
  levels.buildGpuMs = timestamps.elapsedMs(0) + timestamps.elapsedMs(1);
  return levels;
}

}  // namespace lgh::vk
