// The global-illumination benchmark behind `lgh-bench gi` and lghd's POST /v1/benchmark: whole
// frames with light-traced VPLs (settings.gi) on the atrium (or any scene), timed per pass, the
// paper's Tables 2 and 3 and Fig. 5 on this machine (docs/GI.md, docs/BENCHMARKS.md):
//   table 2   per VPL count: VPL generation, LGH construction, render time without shadows and
//             with 1 and 4 shadow samples per pixel, the whole frame, levels, grid lights, overdraw
//   table 3   at one VPL count (100K), 4 samples: the pass breakdown for none / 2x2 / 4x4
//   scaling   render time at the largest VPL count over that at 10K (the paper: 1.65x)
//   quality   at a small resolution: the shadowed frame against the brute force over the same VPLs
//             (one shadow ray per VPL and pixel, no clamp) and against the path tracer, per
//             material class, with the brightness bias, for each alpha and interleaving; the
//             hierarchy alone (unshadowed, against the brute force with its own clamp and none)
//   figures   Fig. 5: the frames and their overdraw heat maps per VPL count, and overdraw against
//             grid lights on log axes (images, for lgh-bench to write)
// The result is typed; giBenchmarkJson() is its JSON document, the same for lgh-bench and lghd.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lgh/bench/render_benchmark.hpp"
#include "lgh/bench/statistics.hpp"
#include "lgh/device_info.hpp"
#include "lgh/image.hpp"
#include "lgh/renderer_options.hpp"
#include "lgh/request.hpp"
#include "lgh/shadow_info.hpp"

namespace lgh::bench {

struct GiBenchmarkOptions {
  std::vector<int> vplCounts{1000, 10000, 100000, 1000000};
  int width = 1280;
  int height = 720;
  SceneSource scene = [] {
    SceneSource source;
    source.builtin = BuiltinScene::Atrium;
    return source;
  }();
  std::string sceneName = "atrium";  // for the report
  int bounces = 3;
  float alpha = 2.0F;  // r_l = alpha h_l here; the paper's (its authors' code) alpha 1
  LightingPath path = LightingPath::Compute;
  float shadowJitter = 0.0F;  // settings.lgh.shadow_jitter (1: the paper's)
  bool depthPrepass = false;  // settings.depth_prepass
  int table3Vpls = 100000;
  std::vector<InterleaveMode> interleaves{InterleaveMode::None, InterleaveMode::Tiles2x2,
                                          InterleaveMode::Tiles4x4};
  int warmupIterations = 3;
  int timedIterations = 10;
  bool overdraw = true;  // Fig. 5: one extra frame per VPL count with the counter
  // Quality runs (small: the brute force traces a ray per VPL and pixel).
  bool quality = true;
  int qualityWidth = 160;
  int qualityHeight = 90;
  int qualityVpls = 100000;
  std::vector<float> qualityAlphas{1.0F, 2.0F, 4.0F};
  int pathTracedSamples = 256;
  std::uint32_t seed = 1;
  RendererOptions renderer;
  std::function<void(const std::string&)> progress;  // one line per finished step; may be empty
};

// One VPL count of Table 2.
struct GiTable2Row {
  int vpls = 0;
  int levels = 0;
  std::uint32_t gridLights = 0;
  std::uint32_t litVpls = 0;        // VPLs with light (paths that left the scene leave none)
  double generationMs = 0.0;        // "gi vpls" (one Vulkan submission: emit, rays, bounces)
  double constructionMs = 0.0;      // "lgh build"
  double renderNoShadowMs = 0.0;    // the frame minus generation and construction, no shadows
  double render1ShadowMs = 0.0;     // ... shadows on, 1 sample per pixel
  double render4ShadowsMs = 0.0;    // ... shadows on, 4 samples per pixel
  double frame4ShadowsMs = 0.0;     // the whole frame with 4 samples (GPU, depth-0 rows)
  std::vector<TimingStats> passes;  // every row of the 4-sample frame
  std::optional<OverdrawStats> overdraw;
};

// One interleaving of Table 3.
struct GiTable3Column {
  InterleaveMode interleave = InterleaveMode::None;
  std::vector<TimingStats> passes;
  double gbufferMs = 0.0;
  double generationMs = 0.0;
  double constructionMs = 0.0;
  double lightingMs = 0.0;    // split + lighting + interleave composite
  double shadowRaysMs = 0.0;  // ray setup (GL) + rays (Vulkan)
  double shadowFilterMs = 0.0;
  double compositingMs = 0.0;  // direct lighting + composite
  double frameMs = 0.0;        // every depth-0 GPU row
  double renderMs = 0.0;       // the frame minus generation and construction (the paper's total)
  double targetMs = 0.0;       // <= this on the GPU test machine (docs/GI.md)
};

// Relative RMSE and bias of one comparison (lgh_testing's MaterialErrors).
struct GiError {
  double relativeRmse = 0.0;
  double psnr = 0.0;
  double diffuseRelativeRmse = 0.0;
  double glossyRelativeRmse = 0.0;
  double bias = 0.0;
  double diffuseBias = 0.0;
  double glossyBias = 0.0;
  double glossyFraction = 0.0;
};

struct GiQualityRun {
  float alpha = 1.0F;
  InterleaveMode interleave = InterleaveMode::None;
  GiError vsVplReference;     // the shadowed frame vs the shadowed brute force (no clamp)
  GiError vsPathTracer;       // the shadowed frame vs the path tracer
  GiError hierarchyOnly;      // unshadowed LGH vs unshadowed brute force with the LGH's clamp
  GiError hierarchyAndClamp;  // unshadowed LGH vs unshadowed brute force without a clamp
};

struct GiQuality {
  int width = 0;
  int height = 0;
  int vpls = 0;
  int pathTracedSamples = 0;
  double bruteForceMs = 0.0;  // the shadowed brute force's "lgh reference" pass
  GiError vplsVsPathTracer;   // the shadowed brute force vs the path tracer
  std::vector<GiQualityRun> runs;
};

// Fig. 5's images, for lgh-bench to write (not in the JSON).
struct GiFigures {
  Image8 heatMaps;      // per VPL count: the frame over its overdraw heat map
  Image8 overdrawPlot;  // mean overdraw per pixel against grid lights, log-log
  Image8 frame;         // the Table 3 frame (no interleaving)
};

struct GiBenchmarkResult {
  DeviceInfo device;
  ShadowInfo shadows;
  GiBenchmarkOptions options;
  std::size_t sceneTriangles = 0;
  std::vector<GiTable2Row> table2;
  std::vector<GiTable3Column> table3;
  double scalingRatio = 0.0;  // render (4 samples) at the largest count / at 10K (0: not run)
  std::optional<GiQuality> quality;
  GiFigures figures;
};

// Creates its own renderer (GL context current on the calling thread while it runs). Throws
// lgh::Error: BadRequest for bad options, Unavailable when the machine cannot trace rays.
GiBenchmarkResult runGiBenchmark(const GiBenchmarkOptions& options);

// The JSON document of a result (`lgh-bench gi --json`, lghd's GET /v1/benchmark/result).
nlohmann::json giBenchmarkJson(const GiBenchmarkResult& result);
// The Markdown report (tables beside the paper's; docs/BENCHMARKS.md quotes it).
std::string giBenchmarkMarkdown(const GiBenchmarkResult& result);

}  // namespace lgh::bench
