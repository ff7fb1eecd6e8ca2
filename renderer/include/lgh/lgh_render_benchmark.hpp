// The LGH rendering benchmark behind `lgh-bench render`: full frames of the built-in demo scene
// lit by VPLs through the hierarchy, for every combination of VPL count, lighting path (raster,
// compute), interleaving (none, 2x2, 4x4) and shadow-sample count - the paper's Table 2 rows and
// Table 3 columns on this machine's GPU. Reports per-pass GPU medians (GL_TIMESTAMP queries), the
// relative RMSE and PSNR of the LGH lighting against the brute-force image of the same VPLs, and
// overdraw statistics (Fig. 5: fragments per pixel for raster, lights evaluated per pixel for
// compute).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "lgh/renderer.hpp"
#include "lgh/request.hpp"

namespace lgh {

struct RenderBenchmarkOptions {
  std::vector<int> vplCounts{1000, 10000, 100000, 1000000};
  int width = 1280;
  int height = 720;
  std::vector<LightingPath> paths{LightingPath::Raster, LightingPath::Compute};
  std::vector<InterleaveMode> interleaves{InterleaveMode::None, InterleaveMode::Tiles2x2,
                                          InterleaveMode::Tiles4x4};
  std::vector<int> shadowSamples{1, 4};
  float alpha = 1.0F;
  // Raster reservoir locks: "paper" (only for 4x4, as Table 3), "none" or "all".
  std::string locks = "paper";
  double warmupSeconds = 1.0;  // frames of the first run before any timing: GPU clocks ramp up
  int warmupIterations = 2;    // untimed frames before each run
  int timedIterations = 10;
  bool reference = true;  // brute-force image per VPL count, RMSE/PSNR per run
  bool overdraw = true;   // one extra frame per run with the overdraw counter
  RendererOptions renderer;
  std::uint32_t seed = 1;
  float vplIntensity = 1.0F;
  std::function<void(const std::string&)> progress;  // one line per finished run; may be empty
};

// Creates its own GL context (current on the calling thread while it runs). Returns
// {"benchmark": "lgh-render", "device", "settings",
//  "references": [{"vpls", "bruteforce_ms"}],
//  "runs": [{"vpls", "path", "interleave", "shadow_samples", "locked", "levels", "grid_lights",
//            "passes": [{"name", "median_ms", "min_ms", "max_ms"}], "build_ms", "lighting_ms"
//            (lighting + interleave split + composite), "render_ms" (every GPU pass but the
//            build), "relative_rmse", "psnr", "overdraw": {"mean", "max", "p50", "p95",
//            "histogram": [{"from", "to", "pixels"}]}}]}.
// Throws lgh::Error (BadRequest for bad options, Unavailable without a context).
nlohmann::json runRenderBenchmark(const RenderBenchmarkOptions& options);

}  // namespace lgh
