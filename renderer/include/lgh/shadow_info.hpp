// What the renderer's shadow side is: the Vulkan tracer of the GL device, or why there is none.
// Reported by lghd's /v1/info; the tracer is made by the first frame that asks for shadows.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace lgh {

struct ShadowInfo {
  // "pending" (no frame has asked for shadows yet), "ready" or "unavailable" (`reason` says why).
  std::string status = "pending";
  std::string reason;
  std::string deviceName;  // the Vulkan device, the GL device's own (UUID match)
  std::string driverName;
  std::string apiVersion;
  bool rayQuery = false;
  bool rayTracingPipeline = false;
  bool externalMemory = false;
  bool externalSemaphores = false;
  // How rays reach Vulkan: "interop", "interop-finish", "pinned" or "staging"; empty before the
  // first batch.
  std::string transport;
  nlohmann::json toJson() const;
};

}  // namespace lgh
