#include "lgh/render_result.hpp"
#include "lgh/resource_stats.hpp"
#include "lgh/shadow_info.hpp"

#include <nlohmann/json.hpp>

namespace lgh {

nlohmann::json DeviceInfo::toJson() const {
  return {{"context_path", contextPath},        {"egl_device_index", eglDeviceIndex},
          {"egl_device_count", eglDeviceCount}, {"gl_vendor", glVendor},
          {"gl_renderer", glRenderer},          {"gl_version", glVersion},
          {"glsl_version", glslVersion},        {"software_renderer", softwareRenderer},
          {"robust_context", robustContext},    {"image_backend", imageBackend}};
}

nlohmann::json ResourceStats::toJson() const {
  nlohmann::json json = {{"gl_objects", glObjects}, {"scene_cache_bytes", sceneCacheBytes}};
  json["gpu_memory_total_kib"] =
      gpuMemoryTotalKiB >= 0 ? nlohmann::json(gpuMemoryTotalKiB) : nlohmann::json();
  json["gpu_memory_available_kib"] =
      gpuMemoryAvailableKiB >= 0 ? nlohmann::json(gpuMemoryAvailableKiB) : nlohmann::json();
  return json;
}

nlohmann::json ShadowInfo::toJson() const {
  nlohmann::json json = {{"status", status}};
  if (!reason.empty()) json["reason"] = reason;
  if (status == "ready") {
    json["device"] = deviceName;
    json["driver"] = driverName;
    json["api_version"] = apiVersion;
    json["ray_query"] = rayQuery;
    json["ray_tracing_pipeline"] = rayTracingPipeline;
    json["external_memory"] = externalMemory;
    json["external_semaphores"] = externalSemaphores;
    json["transport"] = transport.empty() ? nlohmann::json() : nlohmann::json(transport);
    json["process"] = "in-process";
  }
  return json;
}

ImageMetadata RenderResult::metadata() const {
  return {{"Software", "lghd " LGH_VERSION},
          {"lgh:gl_renderer", device.glRenderer},
          {"lgh:context_path", device.contextPath},
          {"lgh:timings", timings.toJson().dump()}};
}

std::vector<std::uint8_t> RenderResult::encode(TaskPool* pool) const {
  return encodeFrame(pixels, output, metadata(), pool);
}

nlohmann::json RenderResult::summaryJson() const {
  return {{"timings", timings.toJson()},
          {"device", device.toJson()},
          {"paths", decisions},
          {"warnings", warnings},
          {"scene_cache_hit", sceneCacheHit}};
}

}  // namespace lgh
