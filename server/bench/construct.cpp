// `lgh-bench construct`: LGH construction on the GPU for a list of VPL counts (the paper's
// Tables 1 and 2). Prints a table (rows: steps; columns: VPL counts, per method) of median GPU
// milliseconds; with --json the JSON document goes to stdout and the table to stderr.
#include <algorithm>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bench/bench_command.hpp"
#include "lgh/bench/construct_benchmark.hpp"
#include "lgh/enum_names.hpp"
#include "lgh/error.hpp"

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
  if (text == "both") return {LghSettings::Method::Gather, LghSettings::Method::Scatter};
  return {cli::enumValue<LghBuildMethod>(text)};
}

// Column labels name the method and the S1 path only when the runs differ in them.
std::string formatTable(const ConstructBenchmarkResult& result, bool labelMethods, bool labelS1) {
  const auto& runs = result.runs;
  std::vector<std::string> columns;
  std::vector<std::string> steps;
  std::size_t maxLevels = 0;
  for (const ConstructRun& run : runs) {
    std::string label = countLabel(run.vpls);
    if (labelS1) label.insert(0, std::string(run.binnedS1 ? "binned" : "direct") + " ");
    if (labelMethods) label.insert(0, std::string(enumName(run.method)) + " ");
    columns.push_back(label);
    for (const TimingStats& step : run.steps) {
      if (std::find(steps.begin(), steps.end(), step.name) == steps.end()) {
        steps.push_back(step.name);
      }
    }
    maxLevels = std::max(maxLevels, run.levelCounts.size());
  }
  std::size_t width = 10;
  for (const auto& column : columns) width = std::max(width, column.size() + 2);
  std::string out = fmt::format("LGH construction on {} ({}), median of {} iterations [GPU ms]\n",
                                result.device.glRenderer, result.device.contextPath,
                                result.options.timedIterations);
  out += fmt::format("{:<18}", "step");
  for (const auto& column : columns) out += fmt::format("{:>{}}", column, width);
  out += '\n';
  auto row = [&](const std::string& name, auto&& cell) {
    out += fmt::format("{:<18}", name);
    for (const ConstructRun& run : runs) out += fmt::format("{:>{}}", cell(run), width);
    out += '\n';
  };
  for (const auto& step : steps) {
    row(step, [&](const ConstructRun& run) -> std::string {
      for (const TimingStats& s : run.steps) {
        if (s.name == step) return fmt::format("{:.3f}", s.medianMs);
      }
      return "-";
    });
  }
  row("total", [](const ConstructRun& run) { return fmt::format("{:.3f}", run.totalMs); });
  row("total, 1 timer",
      [](const ConstructRun& run) { return fmt::format("{:.3f}", run.totalWithoutStepTimersMs); });
  row("levels", [](const ConstructRun& run) { return std::to_string(run.levels); });
  for (std::size_t l = 0; l < maxLevels; ++l) {
    row(fmt::format("|S{}|", l + 1), [&](const ConstructRun& run) -> std::string {
      return l < run.levelCounts.size() ? std::to_string(run.levelCounts[l]) : "-";
    });
  }
  row("grid lights", [](const ConstructRun& run) { return std::to_string(run.gridLights); });
  row("readback CPU ms",
      [](const ConstructRun& run) { return fmt::format("{:.3f}", run.readbackMs); });
  return out;
}

std::string progressLine(const ConstructRun& run) {
  return fmt::format("lgh construct: {} VPLs, {}, {} S1: {} levels, {} grid lights, {:.3f} ms",
                     run.vpls, enumName(run.method), run.binnedS1 ? "binned" : "direct", run.levels,
                     run.gridLights, run.totalMs);
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
  options.progress = [](const ConstructRun& run) { std::cerr << progressLine(run) << '\n'; };
  const ConstructBenchmarkResult result = runConstructBenchmark(options);
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
      ->check(CLI::IsMember([] {
        auto names = cli::enumChoices<LghBuildMethod>();
        names.emplace_back("both");
        return names;
      }()))
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
