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
// BottomLevelBuilds::worthCompacting says why.
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
  GeometryUpload(const VulkanDevice& device, OneTimeCommands& oneTime,
                 const PackedGeometry& geometry)
      : indexOffset_(geometry.positions.size() * kPositionBytes),
        bytes_(indexOffset_ + geometry.indices.size() * kIndexBytes),
        staging_(&oneTime.transientBuffers().get(device,
                                                 {.size = bytes_,
                                                  .usage = ::vk::BufferUsageFlagBits::eTransferSrc,
                                                  .memory = MemoryKind::HostVisible})),
        buffer_(&oneTime.transientBuffers().get(
            device,
            {.size = bytes_,
             .usage = ::vk::BufferUsageFlagBits::eTransferDst |
                      ::vk::BufferUsageFlagBits::eAccelerationStructureBuildInputReadOnlyKHR,
             .memory = MemoryKind::DeviceLocal,
             .deviceAddress = true})) {
    std::memcpy(staging_->mapped(), geometry.positions.data(), indexOffset_);
    std::memcpy(staging_->mapped() + indexOffset_, geometry.indices.data(),
                geometry.indices.size() * kIndexBytes);
  }

  void record(const ::vk::raii::CommandBuffer& commands) const {
    if (bytes_ > 0) {
      commands.copyBuffer(
          staging_->handle(), buffer_->handle(),
          ::vk::BufferCopy{
              .srcOffset = staging_->offset(), .dstOffset = buffer_->offset(), .size = bytes_});
    }
    // Builds read their vertices and indices as shader reads in the build stage.
    memoryBarrier(commands, ::vk::PipelineStageFlagBits::eTransfer,
                  ::vk::AccessFlagBits::eTransferWrite,
                  ::vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR,
                  ::vk::AccessFlagBits::eShaderRead);
  }
  ::vk::DeviceAddress positions() const { return buffer_->address(); }
  ::vk::DeviceAddress indices() const { return buffer_->address() + indexOffset_; }

 private:
  ::vk::DeviceSize indexOffset_;
  ::vk::DeviceSize bytes_;
  // Transient buffers of the device (vk/transient_buffers.hpp): kept until the next build, which
  // retires this one before it uses them.
  const DeviceBuffer* staging_;
  const DeviceBuffer* buffer_;
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
  ::vk::AccelerationStructureKHR destination = nullptr;

  ::vk::AccelerationStructureBuildGeometryInfoKHR info(::vk::DeviceAddress scratch = 0) const {
    return {.type = ::vk::AccelerationStructureTypeKHR::eBottomLevel,
            .flags = BuildFlag::ePreferFastTrace | BuildFlag::eAllowCompaction,
            .mode = ::vk::BuildAccelerationStructureModeKHR::eBuild,
            .dstAccelerationStructure = destination,
            .geometryCount = static_cast<std::uint32_t>(geometries.size()),
            .pGeometries = geometries.data(),
            .scratchData = scratch + scratchOffset};
  }
};

MeshBuild sizeMesh(const VulkanDevice& device, const PackedMesh& mesh, const GeometryUpload& upload,
                   ::vk::DeviceSize& scratchBytes) {
  MeshBuild build;
  std::vector<std::uint32_t> counts;
  for (const PackedPrimitive& primitive : mesh.primitives) {
    build.geometries.push_back(triangles(primitive, upload));
    build.ranges.push_back({.primitiveCount = primitive.triangleCount});
    counts.push_back(primitive.triangleCount);
  }
  const auto sizes = device.device().getAccelerationStructureBuildSizesKHR(
      ::vk::AccelerationStructureBuildTypeKHR::eDevice, build.info(), counts);
  build.bytes = sizes.accelerationStructureSize;
  build.scratchOffset = scratchBytes;
  scratchBytes += alignUp(sizes.buildScratchSize, device.limits().scratchAlignment);
  return build;
}

void recordMeshBuilds(const ::vk::raii::CommandBuffer& commands,
                      const std::vector<MeshBuild>& builds, ::vk::DeviceAddress scratch) {
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
  for (const MeshBuild& build : builds) handles.push_back(build.destination);
  commands.resetQueryPool(*sizes, 0, static_cast<std::uint32_t>(handles.size()));
  memoryBarrier(commands, ::vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR,
                ::vk::AccessFlagBits::eAccelerationStructureWriteKHR,
                ::vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR,
                ::vk::AccessFlagBits::eAccelerationStructureReadKHR);
  commands.writeAccelerationStructuresPropertiesKHR(
      handles, ::vk::QueryType::eAccelerationStructureCompactedSizeKHR, *sizes, 0);
}

std::vector<AccelerationStructure> compact(const VulkanDevice& device, OneTimeCommands& oneTime,
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
  oneTime.submitAndWait(device, [&](const ::vk::raii::CommandBuffer& commands) {
    timestamps.begin(commands, 1);
    for (std::size_t i = 0; i < builds.size(); ++i) {
      commands.copyAccelerationStructureKHR(
          {.src = builds[i].destination,
           .dst = compacted[i].handle(),
           .mode = ::vk::CopyAccelerationStructureModeKHR::eCompact});
    }
    timestamps.end(commands, 1);
  });
  return compacted;
}

}  // namespace

struct BottomLevelBuilds::State {
  State(const VulkanDevice& owner, OneTimeCommands& commands) : device(owner), oneTime(commands) {}
  const VulkanDevice& device;
  OneTimeCommands& oneTime;
  std::optional<GeometryUpload> upload;  // none without triangles
  std::vector<MeshBuild> builds;
  std::vector<std::optional<std::size_t>> structureOfMesh;
  ::vk::DeviceSize scratchBytes = 0;
};

BottomLevelBuilds::BottomLevelBuilds(const VulkanDevice& device, OneTimeCommands& oneTime,
                                     const PackedGeometry& geometry)
    : state_(std::make_unique<State>(device, oneTime)) {
  state_->structureOfMesh.resize(geometry.meshes.size());
  if (geometry.triangleCount == 0) return;
  const GeometryUpload& upload = state_->upload.emplace(device, oneTime, geometry);
  for (std::size_t m = 0; m < geometry.meshes.size(); ++m) {
    if (geometry.meshes[m].empty()) continue;
    state_->structureOfMesh[m] = state_->builds.size();
    state_->builds.push_back(sizeMesh(device, geometry.meshes[m], upload, state_->scratchBytes));
  }
}

BottomLevelBuilds::~BottomLevelBuilds() = default;

bool BottomLevelBuilds::worthCompacting() const {
  ::vk::DeviceSize bytes = 0;
  for (const MeshBuild& build : state_->builds) bytes += build.bytes;
  return bytes >= kCompactFromBytes;
}

::vk::DeviceSize BottomLevelBuilds::storageBytes() const {
  ::vk::DeviceSize bytes = 0;
  for (const MeshBuild& build : state_->builds) {
    bytes += alignUp(build.bytes, AccelerationStructure::kOffsetAlignment);
  }
  return bytes;
}

::vk::DeviceSize BottomLevelBuilds::scratchBytes() const { return state_->scratchBytes; }

BottomLevels BottomLevelBuilds::place(const std::shared_ptr<const DeviceBuffer>& storage,
                                      ::vk::DeviceSize offset) {
  BottomLevels levels;
  levels.structureOfMesh = state_->structureOfMesh;
  levels.structures.reserve(state_->builds.size());
  for (MeshBuild& build : state_->builds) {
    const AccelerationStructure& structure = levels.structures.emplace_back(
        state_->device, ::vk::AccelerationStructureTypeKHR::eBottomLevel, storage, offset,
        build.bytes);
    build.destination = structure.handle();
    offset += alignUp(build.bytes, AccelerationStructure::kOffsetAlignment);
  }
  return levels;
}

void BottomLevelBuilds::recordUpload(const ::vk::raii::CommandBuffer& commands) const {
  if (state_->upload) state_->upload->record(commands);
}

void BottomLevelBuilds::recordBuilds(const ::vk::raii::CommandBuffer& commands,
                                     ::vk::DeviceAddress scratch) const {
  if (!state_->builds.empty()) recordMeshBuilds(commands, state_->builds, scratch);
}

BottomLevels BottomLevelBuilds::buildCompacted() {
  const VulkanDevice& device = state_->device;
  std::vector<MeshBuild>& builds = state_->builds;
  BottomLevels levels;
  levels.structureOfMesh = state_->structureOfMesh;
  if (builds.empty()) return levels;
  std::vector<AccelerationStructure> uncompacted;
  uncompacted.reserve(builds.size());
  for (MeshBuild& build : builds) {
    build.destination =
        uncompacted
            .emplace_back(device, ::vk::AccelerationStructureTypeKHR::eBottomLevel, build.bytes)
            .handle();
  }
  OneTimeCommands& oneTime = state_->oneTime;
  const DeviceBuffer& scratch =
      oneTime.transientBuffers().get(device, accelerationScratch(device, state_->scratchBytes));
  const ::vk::raii::QueryPool sizeQueries(
      device.device(), ::vk::QueryPoolCreateInfo{
                           .queryType = ::vk::QueryType::eAccelerationStructureCompactedSizeKHR,
                           .queryCount = static_cast<std::uint32_t>(builds.size())});
  const TimestampQueries& timestamps = oneTime.timestamps();
  oneTime.submitAndWait(device, [&](const ::vk::raii::CommandBuffer& commands) {
    state_->upload->record(commands);
    timestamps.begin(commands, 0);
    recordMeshBuilds(commands, builds, scratch.address());
    recordSizeQuery(commands, builds, sizeQueries);
    timestamps.end(commands, 0);
  });
  levels.structures = compact(device, oneTime, builds, sizeQueries, timestamps);
  levels.buildGpuMs = timestamps.elapsedMs(0) + timestamps.elapsedMs(1);
  return levels;
}

}  // namespace lgh::vk
