#include "render_response.hpp"

#include <fmt/format.h>

#include "capped_header.hpp"
#include "http_util.hpp"
#include "lgh/base64.hpp"

namespace lghd {
namespace {

// ASCII-only compact JSON: safe in a header value.
std::string headerJson(const nlohmann::json& value) {
  return value.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
}

// Server-Timing metric names are HTTP tokens.
std::string timingToken(const std::string& name) {
  std::string token;
  for (char c : name) token += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return token;
}

// The queue wait first: the render queue's "queue" row when the table has one (it is its first
// row), else `queueMs`.
std::string serverTiming(const lgh::TimingTable& timings, double queueMs) {
  std::string header;
  if (timings.get("queue") < 0.0) header = fmt::format("queue;dur={:.3f}", queueMs);
  for (const lgh::TimingRow& row : timings.rows) {
    if (!header.empty()) header += ", ";
    header += fmt::format("{};dur={:.3f};desc=\"{}\"", timingToken(row.name), row.milliseconds,
                          row.clock == lgh::TimingRow::Clock::Gpu ? "gpu" : "cpu");
  }
  return header;
}

}  // namespace

void setRenderHeaders(httplib::Response& response, const RenderAnswer& answer) {
  const lgh::RenderResult& result = answer.result;
  response.set_header("X-Lgh-Timings", headerJson(result.timings.toJson()));
  response.set_header("Server-Timing", serverTiming(result.timings, answer.queueMs));
  response.set_header("X-Lgh-Renderer", headerSafe(result.device.glRenderer));
  response.set_header("X-Lgh-Context", headerSafe(result.device.contextPath));
  response.set_header("X-Lgh-Cache", result.sceneCacheHit ? "hit" : "miss");
  response.set_header("X-Lgh-Gpu", std::to_string(answer.gpu));
  // Only the EGL device path has a device index (surfaceless and OSMesa do not).
  if (result.device.eglDeviceIndex >= 0) {
    response.set_header("X-Lgh-Gpu-Device", std::to_string(result.device.eglDeviceIndex));
  }
  response.set_header("X-Lgh-Queue-Ms", fmt::format("{:.3f}", answer.queueMs));
  response.set_header("X-Lgh-Render-Ms", fmt::format("{:.3f}", result.timings.get("total")));
  // Both can grow with the client's scene: capped (capped_header.hpp).
  response.set_header("X-Lgh-Paths", cappedJsonObject(result.decisions, kPathsHeaderBytes));
  response.set_header("X-Lgh-Warnings", cappedJsonArray(result.warnings, kWarningsHeaderBytes));
}

nlohmann::json renderResponseJson(const RenderAnswer& answer) {
  const lgh::RenderResult& result = answer.result;
  return {{"image", lgh::base64::encode(result.encoded)},
          {"mime", result.mimeType},
          {"width", answer.width},
          {"height", answer.height},
          {"timings", result.timings.toJson()},
          {"device", result.device.toJson()},
          {"gpu", answer.gpu},
          {"paths", result.decisions},
          {"warnings", result.warnings},
          {"request_id", answer.requestId}};
}

}  // namespace lghd
