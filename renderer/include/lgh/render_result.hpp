// What one render returns: the linear image, its encoding in the requested format, the per-pass
// timing table, the device, the decisions taken and the warnings.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "lgh/device_info.hpp"
#include "lgh/image.hpp"
#include "lgh/request.hpp"
#include "lgh/timing.hpp"

namespace lgh {

struct RenderResult {
  FloatImage image;  // linear RGBA, alpha 0 where nothing was drawn
  TimingTable timings;
  DeviceInfo device;
  // The decisions taken for this frame, by topic: lighting path, cache, interleave, ... Sent as
  // "paths" on the wire (X-Lgh-Paths, the JSON summary).
  std::map<std::string, std::string> decisions;
  std::vector<std::string> warnings;
  bool sceneCacheHit = false;
  std::vector<std::uint8_t> encoded;  // the image in the request's output format
  std::string mimeType;

  // Attributes written into PNG/EXR files: renderer string, context path, timings.
  ImageMetadata metadata() const;
  // The image encoded in `output`'s format.
  std::vector<std::uint8_t> encode(const OutputSettings& output) const;
  // {timings, device, paths, warnings} as JSON (no image).
  nlohmann::json summaryJson() const;
};

}  // namespace lgh
