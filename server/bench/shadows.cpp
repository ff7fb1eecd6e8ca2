// `lgh-bench shadows`: shadowed frames of the demo scene with LGH indirect light at 1280x720 (the
// paper's Table 3 frame), per tracing path and LGH shadow-sample count: shadow rays, filter, rays
// per second and the whole frame; and acceleration-structure builds of the demo and of a generated
// scene of --triangles triangles. Prints a table; with --json the JSON document goes to stdout
// and the table to stderr.
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bench/bench_command.hpp"
#include "lgh/bench/shadow_benchmark.hpp"
#include "lgh/enum_names.hpp"

namespace lgh::bench {
namespace {

struct ShadowFlags {
  int width = 1280;
  int height = 720;
  int vpls = 100000;
  std::vector<int> samples{1, 4};
  std::vector<std::string> paths;
  int filterIterations = 4;
  int iterations = 10;
  int warmup = 3;
  int triangles = 1000000;
  int buildIterations = 3;
  bool json = false;
};

double passMedian(const ShadowRun& run, const std::string& name) {
  for (const TimingStats& pass : run.passes) {
    if (pass.name == name) return pass.medianMs;
  }
  return 0.0;
}

std::string formatTable(const ShadowBenchmarkResult& result) {
  const ShadowBenchmarkOptions& o = result.options;
  std::string out =
      fmt::format("Shadows on {} (Vulkan: {}), {}x{}, {} VPLs, median of {} frames [ms]\n",
                  result.device.glRenderer, result.shadows.deviceName, o.width, o.height,
                  countLabel(o.vpls), o.timedIterations);
  out += fmt::format("{:>9} {:>2} {:>5} {:>14} {:>8} {:>8} {:>8} {:>8} {:>9} {:>10} {:>9}\n",
                     "path", "k", "rays", "transport", "setup", "rays", "filter", "transf.",
                     "rays+filt", "Grays/s", "frame GPU");
  for (const ShadowRun& run : result.runs) {
    out += fmt::format(
        "{:>9} {:>2} {:>5} {:>14} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} {:>9.3f} {:>10.3f} "
        "{:>9.3f}\n",
        enumName(run.path), run.shadowSamples, run.raysPerPixel, run.transport,
        passMedian(run, "shadow ray setup"), run.raysMs, run.filterMs,
        passMedian(run, "shadow transfer"), run.raysMs + run.filterMs, run.raysPerSecond / 1e9,
        run.frameGpuMs);
  }
  for (const ShadowBuild& build : result.builds) {
    out += fmt::format("acceleration structures, {}: {:.3f} ms (median of {}; min {:.3f})\n",
                       build.scene, build.build.medianMs, o.buildIterations, build.build.minMs);
  }
  return out;
}

}  // namespace

Command addShadowsCommand(CLI::App& app, const cli::ContextFlags& context) {
  auto flags = std::make_shared<ShadowFlags>();
  CLI::App* sub = app.add_subcommand(
      "shadows", "time shadowed LGH frames (rays, filter) and acceleration-structure builds");
  sub->add_option("--width", flags->width, "frame width")->capture_default_str();
  sub->add_option("--height", flags->height, "frame height")->capture_default_str();
  sub->add_option("--vpls", flags->vpls, "VPLs of the LGH")->capture_default_str();
  sub->add_option("--samples", flags->samples, "LGH shadow samples per pixel (k), 1..8")
      ->delimiter(',')
      ->capture_default_str();
  sub->add_option("--paths", flags->paths,
                  "tracing paths: ray-query, pipeline (default: every one the device has)")
      ->delimiter(',')
      ->check(CLI::IsMember(cli::enumChoices<ShadowTracing>({"auto"})));
  sub->add_option("--filter-iterations", flags->filterIterations, "a-trous passes")
      ->capture_default_str();
  sub->add_option("--iterations", flags->iterations, "timed frames per run")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--warmup", flags->warmup, "untimed frames first")->capture_default_str();
  sub->add_option("--triangles", flags->triangles,
                  "triangles of the generated scene of the build benchmark (0: none)")
      ->capture_default_str();
  sub->add_option("--build-iterations", flags->buildIterations, "builds per scene")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_flag("--json", flags->json, "JSON on stdout (the table goes to stderr)");
  return {sub, [flags, &context] {
            ShadowBenchmarkOptions options;
            options.width = flags->width;
            options.height = flags->height;
            options.vpls = flags->vpls;
            options.shadowSamples = flags->samples;
            for (const std::string& name : flags->paths) {
              options.paths.push_back(cli::enumValue<ShadowTracing>(name));
            }
            options.filterIterations = flags->filterIterations;
            options.timedIterations = flags->iterations;
            options.warmupIterations = flags->warmup;
            options.buildTriangles = flags->triangles;
            options.buildIterations = flags->buildIterations;
            options.renderer = cli::rendererOptions(context);
            options.progress = [](const ShadowRun& run) {
              std::cerr << fmt::format("{} k={}: rays {:.3f} ms, filter {:.3f} ms\n",
                                       enumName(run.path), run.shadowSamples, run.raysMs,
                                       run.filterMs);
            };
            const ShadowBenchmarkResult result = runShadowBenchmark(options);
            return printResult(result, formatTable(result), flags->json);
          }};
}

}  // namespace lgh::bench
