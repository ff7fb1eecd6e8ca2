// What the passes of one frame report: the image they made, their timing rows, the decisions
// they took and their warnings. Internal: renderer.cpp turns it into the public RenderResult, so
// no pass depends on the façade's types.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "lgh/image.hpp"
#include "lgh/timing.hpp"

namespace lgh {

struct FrameReport {
  FloatImage image;  // linear RGBA, top row first: FramePipeline::render (synchronous) only
  TimingTable timings;
  // Rows known before the GPU timer's but listed after them (the shadow tracer's).
  TimingTable deferredRows;
  std::map<std::string, std::string> decisions;  // topic -> choice ("lgh_lighting" -> "compute")
  std::vector<std::string> warnings;

  void decide(const std::string& topic, std::string choice) {
    decisions[topic] = std::move(choice);
  }
  void warn(std::string warning) { warnings.push_back(std::move(warning)); }
};

}  // namespace lgh
