// Frames of real assets rendered through a Renderer, for the tests that compare two ways of
// making the same frames (the GL worker's uploads, upload staging, overlapped frames).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "lgh/renderer.hpp"

namespace lgh::test {

// A small PNG thumbnail of `asset` (in the asset root), shadows on or off.
inline nlohmann::json thumbnailRequest(const std::string& asset, bool shadows) {
  return {{"scene", {{"asset", asset}}},
          {"settings", {{"shadows", shadows ? "on" : "off"}}},
          {"output", {{"width", 48}, {"height", 40}, {"format", "png"}}}};
}

// Every frame hinted before any is submitted, as the daemon's batches do; the results in order.
inline std::vector<RenderResult> renderHintedFirst(Renderer& renderer,
                                                   const std::vector<nlohmann::json>& frames) {
  std::vector<RenderRequest> requests;
  requests.reserve(frames.size());
  for (const nlohmann::json& frame : frames) requests.push_back(parseRenderRequest(frame));
  for (const RenderRequest& request : requests) renderer.prefetch(request);
  for (const RenderRequest& request : requests) renderer.submit(request);
  std::vector<RenderResult> results;
  while (std::optional<RenderResult> result = renderer.finish(true)) {
    results.push_back(std::move(*result));
  }
  return results;
}

inline std::vector<std::uint8_t> pixelBytes(const RenderResult& result) {
  const std::uint8_t* data = result.pixels.data();
  return {data, data + result.pixels.size()};
}

}  // namespace lgh::test
