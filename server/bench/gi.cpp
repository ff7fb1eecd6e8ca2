// `lgh-bench gi`: global illumination with light-traced VPLs on the atrium (the paper's Tables 2
// and 3 and Fig. 5, and the quality against both references; renderer/bench's gi_benchmark.hpp).
// Prints the Markdown report; with --json the JSON document goes to stdout and the report to
// stderr; with --out-dir the document, the report and the figures are written there too
// (gi.json, gi.md, gi_heatmaps.png, gi_overdraw_plot.png, gi_frame.png).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bench/bench_command.hpp"
#include "bench/bench_options.hpp"
#include "lgh/bench/gi_benchmark.hpp"
#include "lgh/enum_names.hpp"
#include "lgh/error.hpp"
#include "lgh/image.hpp"

namespace lgh::bench {
namespace {

struct GiFlags {
  std::vector<int> vpls{1000, 10000, 100000, 1000000};
  int width = 1280;
  int height = 720;
  std::string scene = "atrium";
  std::string asset;
  int bounces = 3;
  float alpha = 2.0F;
  std::string path = "compute";
  float shadowJitter = 0.0F;
  bool depthPrepass = false;
  int table3Vpls = 100000;
  std::vector<std::string> interleaves = cli::enumChoices<InterleaveMode>();
  int iterations = 10;
  int warmup = 3;
  bool noOverdraw = false;
  bool noQuality = false;
  int qualityWidth = 160;
  int qualityHeight = 90;
  int qualityVpls = 100000;
  std::vector<float> qualityAlphas{1.0F, 2.0F, 4.0F};
  int pathTracedSamples = 256;
  std::uint32_t seed = 1;
  bool json = false;
  std::string outDir;
};

GiBenchmarkOptions optionsFrom(const GiFlags& flags, const cli::ContextFlags& context) {
  GiBenchmarkOptions options;
  options.vplCounts = flags.vpls;
  options.width = flags.width;
  options.height = flags.height;
  if (!flags.asset.empty()) {
    options.scene.kind = SceneSource::Kind::AssetPath;
    options.scene.assetPath = flags.asset;
    options.scene.displayName = flags.asset;
    options.sceneName = flags.asset;
  } else {
    options.scene.kind = SceneSource::Kind::Builtin;
    options.scene.builtin = cli::enumValue<BuiltinScene>(flags.scene);
    options.sceneName = flags.scene;
  }
  options.bounces = flags.bounces;
  options.alpha = flags.alpha;
  options.path = cli::enumValue<LightingPath>(flags.path);
  options.shadowJitter = flags.shadowJitter;
  options.depthPrepass = flags.depthPrepass;
  options.table3Vpls = flags.table3Vpls;
  options.interleaves.clear();
  for (const std::string& name : flags.interleaves) {
    options.interleaves.push_back(cli::enumValue<InterleaveMode>(name));
  }
  options.timedIterations = flags.iterations;
  options.warmupIterations = flags.warmup;
  options.overdraw = !flags.noOverdraw;
  options.quality = !flags.noQuality;
  options.qualityWidth = flags.qualityWidth;
  options.qualityHeight = flags.qualityHeight;
  options.qualityVpls = flags.qualityVpls;
  options.qualityAlphas = flags.qualityAlphas;
  options.pathTracedSamples = flags.pathTracedSamples;
  options.seed = flags.seed;
  options.renderer = cli::rendererOptions(context);
  options.progress = [](const std::string& line) { std::cerr << line << '\n'; };
  return options;
}

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw Error(ErrorCode::Internal, "cannot write the file", path.string());
}

void writeOutputs(const GiBenchmarkResult& result, const std::string& dir) {
  const std::filesystem::path root(dir);
  std::filesystem::create_directories(root);
  writeText(root / "gi.json", giBenchmarkJson(result).dump(2) + "\n");
  writeText(root / "gi.md", giBenchmarkMarkdown(result));
  const auto png = [&](const Image8& image, const char* name) {
    if (image.width > 0) image_io::writeFile(root / name, image_io::encodePng(image));
  };
  png(result.figures.heatMaps, "gi_heatmaps.png");
  png(result.figures.overdrawPlot, "gi_overdraw_plot.png");
  png(result.figures.frame, "gi_frame.png");
}

int runGi(const GiFlags& flags, const cli::ContextFlags& context) {
  const GiBenchmarkResult result = runGiBenchmark(optionsFrom(flags, context));
  if (!flags.outDir.empty()) writeOutputs(result, flags.outDir);
  return printReport(giBenchmarkMarkdown(result), flags.json,
                     [&] { return giBenchmarkJson(result); });
}

}  // namespace

Command addGiCommand(CLI::App& app, const cli::ContextFlags& context) {
  auto flags = std::make_shared<GiFlags>();
  CLI::App* sub = app.add_subcommand(
      "gi",
      "time whole GI frames (light-traced VPLs, LGH, shadows): Tables 2 and 3, Fig. 5, quality");
  sub->fallthrough();
  addPositiveOption(*sub, "--vpls", flags->vpls, "VPL counts of Table 2, comma separated");
  addFrameSizeOptions(*sub, flags->width, flags->height);
  addEnumOption<BuiltinScene>(*sub, "--scene", flags->scene, "built-in scene: atrium, demo");
  sub->add_option("--asset", flags->asset, "a glTF file under --asset-root instead of --scene");
  sub->add_option("--bounces", flags->bounces, "diffuse bounces of the light paths (1..3)")
      ->check(CLI::Range(1, 3))
      ->capture_default_str();
  addPositiveOption(*sub, "--alpha", flags->alpha,
                    "LGH alpha (r_l = alpha h_l; 2 is the paper's alpha 1, docs/LGH.md)");
  addEnumOption<LightingPath>(*sub, "--path", flags->path, "lighting path: compute, raster",
                              {"auto"});
  sub->add_option("--shadow-jitter", flags->shadowJitter,
                  "jitter of the LGH's shadow samples, 0..1 of the paper's (docs/GI.md)")
      ->check(CLI::Range(0.0F, 1.0F))
      ->capture_default_str();
  sub->add_flag("--depth-prepass", flags->depthPrepass,
                "draw depth first, then the G-buffer once per pixel (settings.depth_prepass)");
  addPositiveOption(*sub, "--table3-vpls", flags->table3Vpls, "VPLs of Table 3");
  addEnumOption<InterleaveMode>(*sub, "--interleave", flags->interleaves,
                                "interleavings of Table 3: none, 2x2, 4x4");
  addIterationOptions(*sub, flags->iterations, "timed frames per configuration", flags->warmup,
                      "untimed frames first");
  sub->add_flag("--no-overdraw", flags->noOverdraw, "skip the overdraw frames (Fig. 5)");
  sub->add_flag("--no-quality", flags->noQuality, "skip the references and the error report");
  addPositiveOption(*sub, "--quality-width", flags->qualityWidth, "width of the quality runs");
  addPositiveOption(*sub, "--quality-height", flags->qualityHeight, "height of the quality runs");
  addPositiveOption(*sub, "--quality-vpls", flags->qualityVpls, "VPLs of the quality runs");
  addPositiveOption(*sub, "--quality-alphas", flags->qualityAlphas, "alphas of the quality runs");
  addPositiveOption(*sub, "--pt-samples", flags->pathTracedSamples,
                    "samples per pixel of the path-traced reference");
  sub->add_option("--seed", flags->seed, "seed of the light paths")->capture_default_str();
  sub->add_flag("--json", flags->json, "JSON on stdout (the report goes to stderr)");
  sub->add_option("--out-dir", flags->outDir,
                  "also write gi.json, gi.md and the figures (PNG) into this folder");
  return Command{sub, [flags, &context] { return runGi(*flags, context); }};
}

}  // namespace lgh::bench
