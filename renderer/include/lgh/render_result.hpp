// What one render returns: the frame's pixels as the GPU wrote them (display codes for a PNG,
// linear light for an EXR), their encoding in the requested format, the per-pass timing table,
// the device, the decisions taken and the warnings.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "lgh/device_info.hpp"
#include "lgh/frame_pixels.hpp"
#include "lgh/image.hpp"
#include "lgh/request.hpp"
#include "lgh/timing.hpp"

namespace lgh {

struct RenderResult {
  std::uint64_t frameId = 0;  // Renderer::submit's number for it
  OutputSettings output;      // the request's output: what `pixels` were made for
  // Rows top to bottom; alpha 0 where nothing was drawn. In the renderer's read-back memory
  // (see Renderer, "Frames in flight"): release them once encoded.
  FramePixels pixels;
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
  // The pixels encoded in `output`'s format, on any thread; a large PNG also on `pool`'s idle
  // workers. Needs the pixels (not released).
  std::vector<std::uint8_t> encode(TaskPool* pool = nullptr) const;
  // {timings, device, paths, warnings} as JSON (no image).
  nlohmann::json summaryJson() const;
};

}  // namespace lgh
