#include "lgh/render_result.hpp"

#include <nlohmann/json.hpp>

namespace lgh {

nlohmann::json DeviceInfo::toJson() const {
  return {{"context_path", contextPath},        {"egl_device_index", eglDeviceIndex},
          {"egl_device_count", eglDeviceCount}, {"gl_vendor", glVendor},
          {"gl_renderer", glRenderer},          {"gl_version", glVersion},
          {"glsl_version", glslVersion},        {"software_renderer", softwareRenderer},
          {"image_backend", imageBackend}};
}

ImageMetadata RenderResult::metadata() const {
  return {{"Software", "lghd " LGH_VERSION},
          {"lgh:gl_renderer", device.glRenderer},
          {"lgh:context_path", device.contextPath},
          {"lgh:timings", timings.toJson().dump()}};
}

std::vector<std::uint8_t> RenderResult::encode(const OutputSettings& output) const {
  return encodeImage(image, output, metadata());
}

nlohmann::json RenderResult::summaryJson() const {
  return {{"timings", timings.toJson()},
          {"device", device.toJson()},
          {"paths", decisions},
          {"warnings", warnings},
          {"scene_cache_hit", sceneCacheHit}};
}

}  // namespace lgh
