// What the passes of one frame report: the image they made, their timing rows, the decisions
// they took and their warnings. Internal: renderer.cpp turns it into the public RenderResult, so
// no pass depends on the façade's types.
#pragma once

#include <functional>
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
  // Rows listed after the GPU timer's, written when the frame is taken (writeLateRows): the
  // Vulkan side's, whose GPU times are read then, when the frame's GL fence has passed and with
  // it the Vulkan work it waited for. Drawing the next frame does not wait for them.
  std::vector<std::function<void(TimingTable&)>> lateRows;
  std::map<std::string, std::string> decisions;  // topic -> choice ("lgh_lighting" -> "compute")
  std::vector<std::string> warnings;

  void decide(const std::string& topic, std::string choice) {
    decisions[topic] = std::move(choice);
  }
  void warn(std::string warning) { warnings.push_back(std::move(warning)); }
  // Runs the writers of lateRows once, in the order they were added.
  TimingTable writeLateRows() {
    TimingTable rows;
    for (const auto& write : lateRows) write(rows);
    lateRows.clear();
    return rows;
  }
};

}  // namespace lgh
