// The per-pass timing table every render returns: GPU passes from timer queries, CPU steps from
// a steady clock.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace lgh {

struct TimingRow {
  std::string name;
  enum class Clock { Gpu, Cpu } clock = Clock::Gpu;
  double milliseconds = 0.0;
  int depth = 0;  // 0: a pass of the frame; 1: a step inside the depth-0 pass before it; ...
  // A GPU pass's render-thread time spent issuing it (its GL and Vulkan calls, from its first
  // timer query to its last); < 0 where not measured (CPU rows, rows timed by Vulkan alone).
  double cpuMilliseconds = -1.0;
};

struct TimingTable {
  std::vector<TimingRow> rows;

  void add(std::string name, TimingRow::Clock clock, double ms, int depth = 0);
  // Milliseconds of the row with this name; -1 when absent.
  double get(const std::string& name) const;
  // Appends `later`'s rows. A depth-0 GPU row of `later` whose name is a depth-0 GPU row here
  // is the same work timed twice (a GL pass that waits on the GPU for a Vulkan submission, and
  // that submission's own timestamps): it becomes one row with the larger time, its nested rows
  // under it, so that gpuTotal() counts the work once.
  void appendMerged(const TimingTable& later);
  // The sum of the depth-0 GPU rows (nested steps are inside their pass's time).
  double gpuTotal() const;
  // A fixed-width table for terminals.
  std::string format() const;
  nlohmann::json toJson() const;
};

}  // namespace lgh
