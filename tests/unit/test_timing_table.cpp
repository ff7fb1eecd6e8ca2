// The per-pass timing table: lookups, the GPU total, the terminal table and the JSON form that
// proto/timings.schema.json describes.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lgh/timing.hpp"

namespace lgh {
namespace {

TimingTable sampleTable() {
  TimingTable table;
  table.add("scene_load", TimingRow::Clock::Cpu, 12.5);
  table.add("gbuffer", TimingRow::Clock::Gpu, 1.25);
  table.add("direct_lighting", TimingRow::Clock::Gpu, 0.75);
  return table;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) result.push_back(line);
  return result;
}

TEST(TimingTable, AddKeepsOrder) {
  const TimingTable table = sampleTable();
  ASSERT_EQ(table.rows.size(), 3U);
  EXPECT_EQ(table.rows[0].name, "scene_load");
  EXPECT_EQ(table.rows[0].clock, TimingRow::Clock::Cpu);
  EXPECT_DOUBLE_EQ(table.rows[0].milliseconds, 12.5);
  EXPECT_EQ(table.rows[2].name, "direct_lighting");
}

TEST(TimingTable, GetReturnsMillisecondsOrMinusOne) {
  const TimingTable table = sampleTable();
  EXPECT_DOUBLE_EQ(table.get("gbuffer"), 1.25);
  EXPECT_DOUBLE_EQ(table.get("scene_load"), 12.5);
  EXPECT_DOUBLE_EQ(table.get("missing"), -1.0);
  EXPECT_DOUBLE_EQ(TimingTable{}.get("gbuffer"), -1.0);
}

TEST(TimingTable, GpuTotalSumsOnlyGpuRows) {
  EXPECT_DOUBLE_EQ(sampleTable().gpuTotal(), 2.0);
  EXPECT_DOUBLE_EQ(TimingTable{}.gpuTotal(), 0.0);
}

// Steps inside a pass (the LGH build's) are inside its time: the GPU total counts the pass only.
TEST(TimingTable, NestedStepsAreNotCountedTwice) {
  TimingTable table = sampleTable();
  table.add("lgh build", TimingRow::Clock::Gpu, 3.0);
  table.add("lgh bounds", TimingRow::Clock::Gpu, 1.0, 1);
  table.add("lgh S1", TimingRow::Clock::Gpu, 1.5, 1);
  EXPECT_DOUBLE_EQ(table.gpuTotal(), 5.0);
  const nlohmann::json json = table.toJson();
  EXPECT_FALSE(json[3].contains("depth"));
  EXPECT_EQ(json[4].at("depth"), 1);
  const std::vector<std::string> rows = lines(table.format());
  EXPECT_TRUE(rows[5].starts_with("  lgh bounds")) << rows[5];
  EXPECT_NE(rows.back().find("5.000"), std::string::npos) << rows.back();
}

TEST(TimingTable, FormatIsAlignedWithTotalRow) {
  const std::vector<std::string> rows = lines(sampleTable().format());
  ASSERT_EQ(rows.size(), 5U);  // header, three rows, total
  EXPECT_TRUE(rows[0].starts_with("pass")) << rows[0];
  EXPECT_NE(rows[1].find("scene_load"), std::string::npos);
  EXPECT_NE(rows[1].find("cpu"), std::string::npos);
  EXPECT_NE(rows[1].find("12.500"), std::string::npos);
  EXPECT_NE(rows[2].find("gpu"), std::string::npos);
  EXPECT_TRUE(rows[4].starts_with("total")) << rows[4];
  EXPECT_NE(rows[4].find("2.000"), std::string::npos);
  // Aligned: every line has the same width, the numbers right-aligned in the last column.
  for (const std::string& row : rows) EXPECT_EQ(row.size(), rows[0].size()) << row;
  EXPECT_EQ(rows[1].substr(rows[1].size() - 6), "12.500");
  EXPECT_EQ(rows[2].substr(rows[2].size() - 6), " 1.250");
}

TEST(TimingTable, FormatWidensForLongNames) {
  TimingTable table;
  table.add("a_very_long_pass_name_indeed", TimingRow::Clock::Gpu, 100.0);
  const std::vector<std::string> rows = lines(table.format());
  ASSERT_EQ(rows.size(), 3U);
  for (const std::string& row : rows) EXPECT_EQ(row.size(), rows[0].size()) << row;
}

TEST(TimingTable, EmptyTableFormatsHeaderAndZeroTotal) {
  const std::vector<std::string> rows = lines(TimingTable{}.format());
  ASSERT_EQ(rows.size(), 2U);
  EXPECT_NE(rows[1].find("0.000"), std::string::npos);
}

TEST(TimingTable, ToJsonIsArrayOfPassClockMs) {
  const nlohmann::json expected = nlohmann::json::parse(R"([
    {"pass": "scene_load", "clock": "cpu", "ms": 12.5},
    {"pass": "gbuffer", "clock": "gpu", "ms": 1.25},
    {"pass": "direct_lighting", "clock": "gpu", "ms": 0.75}
  ])");
  EXPECT_EQ(sampleTable().toJson(), expected);
  EXPECT_EQ(TimingTable{}.toJson(), nlohmann::json::array());
}

// The frame's GL rows, then the Vulkan side's: the light paths timed by GL's wait for them
// ("gi vpls", 0.6) and by their own timestamps ("gi vpls", 0.5, with its steps). One row, the
// larger time, its steps under it; the rest appended; the work counted once in the total.
TEST(TimingTable, AppendMergedJoinsTheSameWorkTimedByBothApis) {
  TimingTable frame;
  frame.add("submit", TimingRow::Clock::Cpu, 3.0);
  frame.add("gbuffer", TimingRow::Clock::Gpu, 2.0);
  frame.add("gi vpls", TimingRow::Clock::Gpu, 0.6);
  frame.add("lgh build", TimingRow::Clock::Gpu, 0.3);
  frame.add("lgh bounds", TimingRow::Clock::Gpu, 0.1, 1);
  TimingTable vulkan;
  vulkan.add("gi vpls", TimingRow::Clock::Gpu, 0.5);
  vulkan.add("gi emit", TimingRow::Clock::Gpu, 0.2, 1);
  vulkan.add("gi rays", TimingRow::Clock::Gpu, 0.25, 1);
  vulkan.add("gi transfer", TimingRow::Clock::Cpu, 0.0);
  vulkan.add("shadow rays", TimingRow::Clock::Gpu, 1.5);
  frame.appendMerged(vulkan);
  std::vector<std::string> names;
  for (const TimingRow& row : frame.rows) names.push_back(row.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"submit", "gbuffer", "gi vpls", "gi emit", "gi rays",
                                      "lgh build", "lgh bounds", "gi transfer", "shadow rays"}));
  EXPECT_DOUBLE_EQ(frame.get("gi vpls"), 0.6);
  EXPECT_EQ(frame.rows[3].depth, 1);
  EXPECT_DOUBLE_EQ(frame.gpuTotal(), 2.0 + 0.6 + 0.3 + 1.5);
}

TEST(TimingTable, AppendMergedKeepsTheLargerOfTheTwoTimes) {
  TimingTable frame;
  frame.add("gi vpls", TimingRow::Clock::Gpu, 0.1);  // staging copies: GL timed only the copy
  TimingTable vulkan;
  vulkan.add("gi vpls", TimingRow::Clock::Gpu, 0.9);
  frame.appendMerged(vulkan);
  ASSERT_EQ(frame.rows.size(), 1U);
  EXPECT_DOUBLE_EQ(frame.gpuTotal(), 0.9);
}

// A GL-timed pass carries the render thread's time issuing it (cpu_ms); rows without one (CPU
// steps, Vulkan's own timestamps) have none in JSON, and a merged row keeps GL's.
TEST(TimingTable, CpuMillisecondsOfAPassGoToJsonAndSurviveAMerge) {
  TimingTable frame;
  frame.add("gbuffer", TimingRow::Clock::Gpu, 1.25);
  frame.rows.back().cpuMilliseconds = 0.5;
  frame.add("gi vpls", TimingRow::Clock::Gpu, 0.6);
  frame.rows.back().cpuMilliseconds = 0.25;
  frame.add("submit", TimingRow::Clock::Cpu, 3.0);
  TimingTable vulkan;
  vulkan.add("gi vpls", TimingRow::Clock::Gpu, 0.9);
  frame.appendMerged(vulkan);
  const nlohmann::json expected = nlohmann::json::parse(R"([
    {"pass": "gbuffer", "clock": "gpu", "ms": 1.25, "cpu_ms": 0.5},
    {"pass": "gi vpls", "clock": "gpu", "ms": 0.9, "cpu_ms": 0.25},
    {"pass": "submit", "clock": "cpu", "ms": 3.0}
  ])");
  EXPECT_EQ(frame.toJson(), expected);
}

}  // namespace
}  // namespace lgh
