// Counters of the renderer's scene cache, for metrics.
#pragma once

#include <cstddef>
#include <cstdint>

namespace lgh {

struct SceneCacheStats {
  std::uint64_t hits = 0;
  std::uint64_t misses = 0;
  std::size_t entries = 0;
  std::size_t bytes = 0;
  // Upload staging memory (RendererOptions::uploadStagingBytes; 0: none) and its bytes held by
  // scenes parsed and not uploaded yet, or uploaded and not yet copied by the GPU.
  std::size_t stagingBytes = 0;
  std::size_t stagingBytesInUse = 0;
  // GL storage of freed scenes kept for later ones (RGBA8 textures, geometry buffers; none with
  // the GL worker): new objects that took kept storage, and the bytes kept now (outside `bytes`).
  std::uint64_t recycledTextures = 0;
  std::uint64_t recycledBuffers = 0;
  std::size_t keptStorageBytes = 0;
};

}  // namespace lgh
