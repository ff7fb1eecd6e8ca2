// What a renderer holds on the GPU, for watching a long-running service for leaks: live GL
// objects by kind (every context of the process) and the GPU's memory where the driver reports
// it (GL_NVX_gpu_memory_info: NVIDIA).
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace lgh {

struct ResourceStats {
  std::map<std::string, std::int64_t> glObjects;  // "buffer", "texture", ... -> live count
  std::int64_t gpuMemoryTotalKiB = -1;            // -1: the driver does not say
  std::int64_t gpuMemoryAvailableKiB = -1;
  std::size_t sceneCacheBytes =
      0;  // GPU memory of the cached scenes (GL + acceleration structures)
  nlohmann::json toJson() const;
};

}  // namespace lgh
