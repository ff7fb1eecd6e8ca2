#include <algorithm>
#include <string_view>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "lgh/timing.hpp"

namespace lgh {
namespace {

const char* clockName(TimingRow::Clock clock) {
  return clock == TimingRow::Clock::Gpu ? "gpu" : "cpu";
}

}  // namespace

void TimingTable::add(std::string name, TimingRow::Clock clock, double ms, int depth) {
  rows.push_back({std::move(name), clock, ms, depth});
}

void TimingTable::appendMerged(const TimingTable& later) {
  auto row = later.rows.begin();
  while (row != later.rows.end()) {
    auto subtreeEnd = std::next(row);
    while (subtreeEnd != later.rows.end() && subtreeEnd->depth > row->depth) ++subtreeEnd;
    const auto same = std::find_if(rows.begin(), rows.end(), [&](const TimingRow& existing) {
      return existing.depth == 0 && existing.clock == TimingRow::Clock::Gpu &&
             existing.name == row->name;
    });
    if (row->depth == 0 && row->clock == TimingRow::Clock::Gpu && same != rows.end()) {
      same->milliseconds = std::max(same->milliseconds, row->milliseconds);
      same->cpuMilliseconds = std::max(same->cpuMilliseconds, row->cpuMilliseconds);
      auto after = std::next(same);
      while (after != rows.end() && after->depth > 0) ++after;
      rows.insert(after, std::next(row), subtreeEnd);
    } else {
      rows.insert(rows.end(), row, subtreeEnd);
    }
    row = subtreeEnd;
  }
}

double TimingTable::get(const std::string& name) const {
  const auto it = std::find_if(rows.begin(), rows.end(),
                               [&](const TimingRow& row) { return row.name == name; });
  return it == rows.end() ? -1.0 : it->milliseconds;
}

double TimingTable::gpuTotal() const {
  double total = 0.0;
  for (const TimingRow& row : rows) {
    if (row.clock == TimingRow::Clock::Gpu && row.depth == 0) total += row.milliseconds;
  }
  return total;
}

// pass      clock        ms
// gbuffer   gpu       1.234
// ...
// total gpu           5.678
// GPU and CPU times overlap (the CPU waits on the GPU), so only the GPU rows are summed: a sum
// over both clocks would count the same milliseconds twice.
std::string TimingTable::format() const {
  constexpr std::string_view kTotalLabel = "total gpu";
  std::size_t nameWidth = std::string_view("pass").size();
  for (const TimingRow& row : rows) {
    nameWidth = std::max(nameWidth, row.name.size() + 2 * static_cast<std::size_t>(row.depth));
  }
  nameWidth = std::max(nameWidth, kTotalLabel.size());

  constexpr int kMsWidth = 10;
  std::string text =
      fmt::format("{:<{}}  {:<5}  {:>{}}\n", "pass", nameWidth, "clock", "ms", kMsWidth);
  for (const TimingRow& row : rows) {
    const std::string name = std::string(2 * static_cast<std::size_t>(row.depth), ' ') + row.name;
    text += fmt::format("{:<{}}  {:<5}  {:>{}.3f}\n", name, nameWidth, clockName(row.clock),
                        row.milliseconds, kMsWidth);
  }
  text +=
      fmt::format("{:<{}}  {:<5}  {:>{}.3f}\n", kTotalLabel, nameWidth, "", gpuTotal(), kMsWidth);
  return text;
}

nlohmann::json TimingTable::toJson() const {
  nlohmann::json array = nlohmann::json::array();
  for (const TimingRow& row : rows) {
    nlohmann::json entry = {
        {"pass", row.name}, {"clock", clockName(row.clock)}, {"ms", row.milliseconds}};
    if (row.depth > 0) entry["depth"] = row.depth;
    if (row.cpuMilliseconds >= 0.0) entry["cpu_ms"] = row.cpuMilliseconds;
    array.push_back(std::move(entry));
  }
  return array;
}

}  // namespace lgh
