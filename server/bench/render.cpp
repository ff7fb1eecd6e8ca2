// `lgh-bench render`: full LGH frames of the demo scene for a list of VPL counts, both lighting
// paths, each interleaving and shadow-sample count (the paper's Tables 2 and 3, Fig. 5), with the
// relative RMSE / PSNR of every run against the brute-force image. Prints one row per run (median
// GPU milliseconds); with --json the JSON document goes to stdout and the table to stderr.
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bench/bench_command.hpp"
#include "bench/bench_options.hpp"
#include "lgh/bench/render_benchmark.hpp"
#include "lgh/enum_names.hpp"
#include "lgh/error.hpp"

namespace lgh::bench {
namespace {

struct RenderFlags {
  std::vector<int> vpls{1000, 10000, 100000, 1000000};
  int width = 1280;
  int height = 720;
  std::vector<std::string> paths = cli::enumChoices<LightingPath>({"auto"});
  std::vector<std::string> interleaves = cli::enumChoices<InterleaveMode>();
  std::vector<int> samples{1, 4};
  float alpha = 1.0F;
  std::string locks = "paper";
  int iterations = 10;
  int warmup = 2;
  bool noReference = false;
  bool noOverdraw = false;
  bool json = false;
  std::uint32_t seed = 1;
  float intensity = 1.0F;
};

double passMedian(const RenderRun& run, const std::string& name) {
  for (const TimingStats& pass : run.passes) {
    if (pass.name == name) return pass.medianMs;
  }
  return 0.0;
}

std::string formatTable(const RenderBenchmarkResult& result) {
  const RenderBenchmarkOptions& settings = result.options;
  std::string out =
      fmt::format("LGH rendering on {} ({}), {}x{}, alpha {}, median of {} frames [GPU ms]\n",
                  result.device.glRenderer, result.device.contextPath, settings.width,
                  settings.height, settings.alpha, settings.timedIterations);
  out += fmt::format(
      "{:>6} {:>8} {:>6} {:>2} {:>6} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>9} {:>7} {:>9} {:>6}\n",
      "VPLs", "path", "inter.", "k", "locked", "gbuffer", "build", "split", "light", "compos.",
      "lighting", "render", "relRMSE", "PSNR dB", "overdr");
  for (const RenderRun& run : result.runs) {
    std::string rmse = "-";
    std::string psnr = "-";
    if (run.error) {
      rmse = fmt::format("{:.4f}", run.error->relativeRmse);
      psnr = std::isfinite(run.error->psnr) ? fmt::format("{:.2f}", run.error->psnr) : "inf";
    }
    const std::string overdraw =
        run.overdraw && run.overdraw->pixels > 0 ? fmt::format("{:.1f}", run.overdraw->mean) : "-";
    out += fmt::format(
        "{:>6} {:>8} {:>6} {:>2} {:>6} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} "
        "{:>9.3f} "
        "{:>7} {:>9} {:>6}\n",
        countLabel(run.vpls), enumName(run.path), enumName(run.interleave), run.shadowSamples,
        run.locked ? "yes" : "no", passMedian(run, "gbuffer"), run.buildMs,
        passMedian(run, "lgh interleave split"), passMedian(run, "lgh lighting"),
        passMedian(run, "lgh interleave composite"), run.lightingMs, run.renderMs, rmse, psnr,
        overdraw);
  }
  for (const RenderReference& reference : result.references) {
    out += fmt::format("brute-force reference, {} VPLs: {:.3f} ms\n", countLabel(reference.vpls),
                       reference.bruteforceMs);
  }
  return out;
}

std::string progressLine(const RenderRun& run) {
  std::string line = fmt::format(
      "lgh render: {} VPLs, {}, interleave {}, {} sample(s){}: lighting {:.3f} ms, render {:.3f} "
      "ms",
      run.vpls, enumName(run.path), enumName(run.interleave), run.shadowSamples,
      run.locked ? ", locked" : "", run.lightingMs, run.renderMs);
  if (run.error) line += fmt::format(", rel. RMSE {:.4f}", run.error->relativeRmse);
  if (run.overdraw && run.overdraw->pixels > 0) {
    line += fmt::format(", overdraw {:.1f}", run.overdraw->mean);
  }
  return line;
}

template <typename Enum>
std::vector<Enum> parseEnums(const std::vector<std::string>& names) {
  std::vector<Enum> values;
  values.reserve(names.size());
  for (const auto& name : names) values.push_back(cli::enumValue<Enum>(name));
  return values;
}

int runRender(const RenderFlags& flags, const cli::ContextFlags& context) {
  RenderBenchmarkOptions options;
  options.vplCounts = flags.vpls;
  options.width = flags.width;
  options.height = flags.height;
  options.paths = parseEnums<LightingPath>(flags.paths);
  options.interleaves = parseEnums<InterleaveMode>(flags.interleaves);
  options.shadowSamples = flags.samples;
  options.alpha = flags.alpha;
  options.locks = flags.locks;
  options.warmupIterations = flags.warmup;
  options.timedIterations = flags.iterations;
  options.reference = !flags.noReference;
  options.overdraw = !flags.noOverdraw;
  options.renderer = cli::rendererOptions(context);
  options.seed = flags.seed;
  options.vplIntensity = flags.intensity;
  options.progress = [](const RenderRun& run) { std::cerr << progressLine(run) << '\n'; };
  const RenderBenchmarkResult result = runRenderBenchmark(options);
  return printResult(result, formatTable(result), flags.json);
}

}  // namespace

Command addRenderCommand(CLI::App& app, const cli::ContextFlags& context) {
  auto flags = std::make_shared<RenderFlags>();
  CLI::App* sub = app.add_subcommand(
      "render", "time LGH lighting (raster and compute paths) on the demo scene with VPLs");
  sub->fallthrough();
  addPositiveOption(*sub, "--vpls", flags->vpls, "VPL counts, comma separated");
  addFrameSizeOptions(*sub, flags->width, flags->height);
  addEnumOption<LightingPath>(*sub, "--paths", flags->paths, "lighting paths: raster, compute",
                              {"auto"});
  addEnumOption<InterleaveMode>(*sub, "--interleave", flags->interleaves,
                                "interleaving: none, 2x2, 4x4");
  sub->add_option("--samples", flags->samples, "shadow samples per pixel (1..8), comma separated")
      ->delimiter(',')
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  addPositiveOption(*sub, "--alpha", flags->alpha, "hierarchy blending parameter alpha");
  sub->add_option("--locks", flags->locks,
                  "raster reservoir locks: paper (4x4 only, Table 3), none, all")
      ->check(CLI::IsMember({"paper", "none", "all"}))
      ->capture_default_str();
  addIterationOptions(*sub, flags->iterations, "timed frames per run", flags->warmup,
                      "untimed frames first");
  sub->add_flag("--no-reference", flags->noReference, "skip the brute-force image and the RMSE");
  sub->add_flag("--no-overdraw", flags->noOverdraw, "skip the overdraw statistics");
  sub->add_flag("--json", flags->json, "JSON on stdout (the table goes to stderr)");
  sub->add_option("--seed", flags->seed, "VPL sampling and reservoir seed")->capture_default_str();
  sub->add_option("--intensity", flags->intensity, "VPL intensity scale")->capture_default_str();
  return Command{sub, [flags, &context] { return runRender(*flags, context); }};
}

}  // namespace lgh::bench
