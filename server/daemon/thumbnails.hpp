// A thumbnail batch: assets (paths in the asset root, or uploaded files) x views, each rendered
// with an auto-framed camera at one size. The options are validated once for the whole batch (a
// bad width fails the batch with 4xx); what is wrong with one asset only becomes that item's
// error, so one bad asset never sinks the batch.
//
// JSON body (every member optional but assets, which uploads may replace):
//   {"assets": ["a.glb", "dir/b.gltf"], "width": 256, "height": 256,
//    "view_direction": [1, 0.6, 1.4], "views": [{"name": "front", "direction": [0, 0, 1]}],
//    "margin": 1.1, "transparent_background": false, "format": "zip" | "ndjson",
//    "name_template": "{name}_{view}.png", "settings": {...render settings...}}
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "api_error.hpp"
#include "lgh/request.hpp"
#include "uploads.hpp"

namespace lghd {

struct ThumbnailItem {
  std::size_t index = 0;
  std::string asset;       // the path or upload name, as the client gave it
  std::string assetField;  // where the client gave it: "/assets/<i>" or "file"
  std::string view;        // the view's name
  std::string fileName;    // of the PNG in the ZIP or NDJSON line, unique in the batch
  std::optional<lgh::RenderRequest> request;  // empty when the item failed before rendering
  std::optional<ApiError> error;
};

struct ThumbnailBatch {
  enum class Format { Zip, Ndjson };
  Format format = Format::Zip;
  std::vector<ThumbnailItem> items;
};

// Throws ApiError (400/413/422) for problems of the whole batch.
ThumbnailBatch parseThumbnailBatch(const nlohmann::json& body,
                                   const std::vector<UploadedFile>& uploads,
                                   const lgh::RequestLimits& limits, int maxBatch);

// `name_template` with {name}, {view} and {index} replaced; throws ApiError 400 for another
// placeholder or an unbalanced brace.
std::string expandNameTemplate(const std::string& nameTemplate, const std::string& name,
                               const std::string& view, std::size_t index);

// The ZIP file comment of a thumbnail: {"gpu":N}, the render worker (its place in --gpus) that
// rendered it; empty for none (gpu < 0).
std::string zipCommentNamingGpu(int gpu);

}  // namespace lghd
