// How a finished render is answered: the image with its timing table in headers, or the JSON of
// proto/render-response.schema.json.
#pragma once

#include <string>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "lgh/renderer.hpp"

namespace lghd {

struct RenderAnswer {
  const lgh::RenderResult& result;
  int width = 0;
  int height = 0;
  double queueMs = 0.0;
  std::string requestId;
  int gpu = -1;  // the render worker it ran on (its place in --gpus)
};

// X-Lgh-Timings (compact JSON), Server-Timing, X-Lgh-Renderer, X-Lgh-Context, X-Lgh-Cache,
// X-Lgh-Queue-Ms, X-Lgh-Render-Ms, X-Lgh-Paths, X-Lgh-Warnings, X-Lgh-Gpu (the render worker) and
// X-Lgh-Gpu-Device (its EGL device).
void setRenderHeaders(httplib::Response& response, const RenderAnswer& answer);

// {image, mime, width, height, timings, device, gpu, paths, warnings, request_id}
nlohmann::json renderResponseJson(const RenderAnswer& answer);

}  // namespace lghd
