// The bottom-level acceleration structures of a scene: one per mesh with triangles, a geometry
// per primitive (opaque), built for fast tracing. The positions and indices go up through a
// staging buffer. The builds are sized first, then take one of two ways:
// - a large scene (compaction pays off) builds and compacts them in submissions of its own
//   (buildCompacted), each structure in a buffer of its own;
// - a small one places them in a buffer it shares with the top level (place) and records their
//   builds into the submission that builds the top level too (record), which saves an
//   allocation per mesh and a wait for the GPU.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "vk/acceleration_structure.hpp"

namespace lgh::vk {

class OneTimeCommands;
class VulkanDevice;
struct PackedGeometry;

struct BottomLevels {
  std::vector<AccelerationStructure> structures;
  // For each of the scene's meshes, its structure's index in `structures`; nullopt: no triangles.
  std::vector<std::optional<std::size_t>> structureOfMesh;
  double buildGpuMs = 0.0;  // the builds and the compaction (buildCompacted only)
};

class BottomLevelBuilds {
 public:
  // Stages the geometry and sizes each mesh's structure; `geometry` must outlive this object.
  // Its staging and geometry buffers are `oneTime`'s transient ones, its submissions `oneTime`'s.
  BottomLevelBuilds(const VulkanDevice& device, OneTimeCommands& oneTime,
                    const PackedGeometry& geometry);
  ~BottomLevelBuilds();
  BottomLevelBuilds(const BottomLevelBuilds&) = delete;
  BottomLevelBuilds& operator=(const BottomLevelBuilds&) = delete;

  // Compaction halves a bottom level's memory or so, but costs a round trip to the GPU (the
  // compacted sizes are read back before the copies) and a second allocation per mesh: worth it
  // for large scenes, not for the small ones a thumbnail batch loads by the dozen.
  bool worthCompacting() const;

  // Builds, compacts and waits for the GPU (two submissions).
  BottomLevels buildCompacted();

  // Every structure at an AccelerationStructure::kOffsetAlignment offset.
  ::vk::DeviceSize storageBytes() const;
  ::vk::DeviceSize scratchBytes() const;
  // Creates the structures in `storage` (storageBytes() of it from `offset`, a multiple of
  // kOffsetAlignment); they are built once the commands of record() have run.
  BottomLevels place(const std::shared_ptr<const DeviceBuffer>& storage, ::vk::DeviceSize offset);
  // Records the copy of the staged geometry into device memory (the staging memory lives as
  // long as this object), then, after it, the builds into the placed structures (`scratch`:
  // scratchBytes() of device memory, aligned as the device wants).
  void recordUpload(const ::vk::raii::CommandBuffer& commands) const;
  void recordBuilds(const ::vk::raii::CommandBuffer& commands, ::vk::DeviceAddress scratch) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace lgh::vk
