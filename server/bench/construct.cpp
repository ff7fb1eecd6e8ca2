// `lgh-bench construct`: LGH construction on the GPU for a list of VPL counts (the paper's
// Tables 1 and 2). Prints a table (rows: steps; columns: VPL counts, per method) of median GPU
// milliseconds; with --json the JSON document goes to stdout and the table to stderr.
#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench/bench_command.hpp"
#include "lgh/error.hpp"
#include "lgh/lgh_benchmark.hpp"

namespace lgh::bench {
namespace {

struct ConstructFlags {
  std::vector<int> vpls{1000, 10000, 100000, 1000000};
  std::string method = "gather";
  std::string levels = "auto";
  int iterations = 10;
  int warmup = 2;
  bool json = false;
  bool perLevel = false;
  std::string atomics = "auto";
  std::string s1 = "auto";
  std::uint32_t seed = 1;
  float flux = 10.0F;
  std::string order = "random";
  int width = 1280;  // accepted for uniformity with the render subcommands; unused here
  int height = 720;
};

std::string countLabel(int count) {
  if (count >= 1000000 && count % 1000000 == 0) return fmt::format("{}M", count / 1000000);
  if (count >= 1000 && count % 1000 == 0) return fmt::format("{}K", count / 1000);
  return std::to_string(count);
}

int parseLevels(const std::string& text) {
  if (text == "auto") return 0;
  try {
    std::size_t used = 0;
    const int levels = std::stoi(text, &used);
    if (used == text.size() && levels >= 1) return levels;
  } catch (const std::exception&) {
  }
  throw Error(ErrorCode::BadRequest,
              "--levels takes a positive number or 'auto', not '" + text + "'");
}

std::vector<LghSettings::Method> parseMethods(const std::string& text) {
  if (text == "gather") return {LghSettings::Method::Gather};
  if (text == "scatter") return {LghSettings::Method::Scatter};
  return {LghSettings::Method::Gather, LghSettings::Method::Scatter};
}

// Column labels name the method and the S1 path only when the runs differ in them.
std::string formatTable(const nlohmann::json& result, bool labelMethods, bool labelS1) {
  const auto& runs = result["runs"];
  std::vector<std::string> columns;
  std::vector<std::string> steps;
  std::size_t maxLevels = 0;
  for (const auto& run : runs) {
    std::string label = countLabel(run["vpls"].get<int>());
    if (labelS1) label.insert(0, run["s1"].get<std::string>() + " ");
    if (labelMethods) label.insert(0, run["method"].get<std::string>() + " ");
    columns.push_back(label);
    for (const auto& step : run["steps"]) {
      const auto name = step["name"].get<std::string>();
      if (std::find(steps.begin(), steps.end(), name) == steps.end()) steps.push_back(name);
    }
    maxLevels = std::max(maxLevels, run["level_counts"].size());
  }
  std::size_t width = 10;
  for (const auto& column : columns) width = std::max(width, column.size() + 2);
  std::string out = fmt::format("LGH construction on {} ({}), median of {} iterations [GPU ms]\n",
                                result["device"].value("gl_renderer", std::string("?")),
                                result["device"].value("context_path", std::string("?")),
                                result["settings"]["timed_iterations"].get<int>());
  out += fmt::format("{:<18}", "step");
  for (const auto& column : columns) out += fmt::format("{:>{}}", column, width);
  out += '\n';
  auto row = [&](const std::string& name, auto&& cell) {
    out += fmt::format("{:<18}", name);
    for (const auto& run : runs) out += fmt::format("{:>{}}", cell(run), width);
    out += '\n';
  };
  for (const auto& step : steps) {
    row(step, [&](const nlohmann::json& run) -> std::string {
      for (const auto& s : run["steps"]) {
        if (s["name"] == step) return fmt::format("{:.3f}", s["median_ms"].get<double>());
      }
      return "-";
    });
  }
  row("total", [](const nlohmann::json& run) {
    return fmt::format("{:.3f}", run["total_ms"].get<double>());
  });
  row("total, 1 timer", [](const nlohmann::json& run) {
    return fmt::format("{:.3f}", run["total_without_step_timers_ms"].get<double>());
  });
  row("levels", [](const nlohmann::json& run) { return std::to_string(run["levels"].get<int>()); });
  for (std::size_t l = 0; l < maxLevels; ++l) {
    row(fmt::format("|S{}|", l + 1), [&](const nlohmann::json& run) -> std::string {
      const auto& counts = run["level_counts"];
      return l < counts.size() ? std::to_string(counts[l].get<std::uint32_t>()) : "-";
    });
  }
  row("grid lights", [](const nlohmann::json& run) {
    return std::to_string(run["grid_lights"].get<std::uint32_t>());
  });
  row("readback CPU ms", [](const nlohmann::json& run) {
    return fmt::format("{:.3f}", run["readback_ms"].get<double>());
  });
  return out;
}

int runConstruct(const ConstructFlags& flags, const cli::ContextFlags& context) {
  ConstructBenchmarkOptions options;
  options.vplCounts = flags.vpls;
  options.methods = parseMethods(flags.method);
  options.levels = parseLevels(flags.levels);
  options.warmupIterations = flags.warmup;
  options.timedIterations = flags.iterations;
  options.perLevelTimings = flags.perLevel;
  options.atomics = flags.atomics;
  options.s1 = flags.s1;
  options.renderer = cli::rendererOptions(context);
  options.seed = flags.seed;
  options.totalFlux = flags.flux;
  options.vplOrder = flags.order;
  options.progress = [](const std::string& line) { std::cerr << line << '\n'; };
  const nlohmann::json result = runConstructBenchmark(options);
  return printResult(result, formatTable(result, options.methods.size() > 1, options.s1 == "both"),
                     flags.json);
}

}  // namespace

Command addConstructCommand(CLI::App& app, const cli::ContextFlags& context) {
  auto flags = std::make_shared<ConstructFlags>();
  CLI::App* sub = app.add_subcommand(
      "construct", "time the LGH build on the GPU from VPLs sampled on the demo scene");
  sub->fallthrough();
  sub->add_option("--vpls", flags->vpls, "VPL counts, comma separated")
      ->delimiter(',')
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--method", flags->method,
                  "gather (from S1, the paper's), scatter (every level), both")
      ->check(CLI::IsMember({"gather", "scatter", "both"}))
      ->capture_default_str();
  sub->add_option("--levels", flags->levels, "levels L, or auto (largest L with |S1| < N/2)")
      ->capture_default_str();
  sub->add_option("--iterations", flags->iterations, "timed builds per column")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--warmup", flags->warmup, "untimed builds first")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sub->add_flag("--json", flags->json, "JSON on stdout (the table goes to stderr)");
  sub->add_flag("--per-level", flags->perLevel, "gather: one dispatch and row per level (Table 1)");
  sub->add_option("--atomics", flags->atomics, "auto, float (GL_NV_shader_atomic_float), fixed")
      ->check(CLI::IsMember({"auto", "float", "fixed"}))
      ->capture_default_str();
  sub->add_option("--s1", flags->s1,
                  "S1 accumulation: direct (global atomics per light), binned (by tile, in shared "
                  "memory), auto (binned for large inputs), both")
      ->check(CLI::IsMember({"auto", "direct", "binned", "both"}))
      ->capture_default_str();
  sub->add_option("--seed", flags->seed, "VPL sampling seed")->capture_default_str();
  sub->add_option("--vpl-order", flags->order,
                  "random (as sampled) or morton (sorted along a Z-order curve first)")
      ->check(CLI::IsMember({"random", "morton"}))
      ->capture_default_str();
  sub->add_option("--flux", flags->flux, "total VPL flux")->capture_default_str();
  sub->add_option("--width", flags->width,
                  "accepted for uniformity with other subcommands; unused");
  sub->add_option("--height", flags->height,
                  "accepted for uniformity with other subcommands; unused");
  return Command{sub, [flags, &context] { return runConstruct(*flags, context); }};
}

}  // namespace lgh::bench
