// The LGH rendering benchmark behind `lgh-bench render`: full frames of the built-in demo scene
// lit by VPLs through the hierarchy, for every combination of VPL count, lighting path (raster,
// compute), interleaving (none, 2x2, 4x4) and shadow-sample count - the paper's Table 2 rows and
// Table 3 columns on this machine's GPU. Reports per-pass GPU medians (GL_TIMESTAMP queries), the
// relative RMSE and PSNR of the LGH lighting against the brute-force image of the same VPLs, and
// overdraw statistics (Fig. 5: fragments per pixel for raster, lights evaluated per pixel for
// compute). The result is typed; lgh-bench prints it: the table and progress lines in
// server/bench/render.cpp, the JSON of `--json` in server/bench/result_json.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lgh/bench/statistics.hpp"
#include "lgh/device_info.hpp"
#include "lgh/image.hpp"
#include "lgh/renderer_options.hpp"
#include "lgh/request.hpp"

namespace lgh::bench {

struct RenderRun;

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
  std::function<void(const RenderRun&)> progress;  // called per finished run; may be empty
};

// Overdraw over the covered pixels: fragments (raster) or lights evaluated (compute) per pixel.
struct OverdrawStats {
  struct Bin {
    std::uint64_t from = 0;  // [from, to): power-of-two bins (Fig. 5 is a log heat map)
    std::uint64_t to = 0;
    std::size_t pixels = 0;
  };
  std::size_t pixels = 0;  // covered pixels; 0: nothing covered, no statistics
  double mean = 0.0;
  std::uint32_t max = 0;
  std::uint32_t p50 = 0;
  std::uint32_t p95 = 0;
  std::vector<Bin> histogram;
};

// Overdraw statistics of per-pixel counts (GL order, row 0 at the bottom) over the pixels that
// `coverage` (top row first, alpha > 0) covers.
OverdrawStats overdrawStats(const std::vector<std::uint32_t>& counts, const FloatImage& coverage);

// The LGH lighting (indirect image) against the brute-force image of the same VPLs.
struct ReferenceError {
  double relativeRmse = 0.0;
  double psnr = 0.0;  // dB; +inf when identical
};

// One configuration: VPL count, path, interleaving, shadow samples, locks.
struct RenderRun {
  int vpls = 0;
  LightingPath path = LightingPath::Compute;
  InterleaveMode interleave = InterleaveMode::None;
  int shadowSamples = 1;
  bool locked = false;  // raster reservoir locks
  int levels = 0;       // the hierarchy's levels and grid lights
  std::uint32_t gridLights = 0;
  std::vector<TimingStats> passes;        // every GPU pass of the frame, in frame order
  double buildMs = 0.0;                   // median of "lgh build"
  double lightingMs = 0.0;                // lighting + interleave split + composite (medians)
  double renderMs = 0.0;                  // every GPU pass but the build (medians)
  std::optional<ReferenceError> error;    // with options.reference
  std::optional<OverdrawStats> overdraw;  // with options.overdraw
};

// The brute-force reference frame of one VPL count.
struct RenderReference {
  int vpls = 0;
  double bruteforceMs = 0.0;  // its "lgh reference" pass
};

struct RenderBenchmarkResult {
  DeviceInfo device;
  RenderBenchmarkOptions options;  // the settings it ran with
  std::string scene = "demo";
  std::vector<RenderReference> references;  // in the order first needed
  std::vector<RenderRun> runs;  // per VPL count, path, interleaving and sample count, nested
};

// Creates its own GL context (current on the calling thread while it runs). Throws lgh::Error
// (BadRequest for bad options, Unavailable without a context).
RenderBenchmarkResult runRenderBenchmark(const RenderBenchmarkOptions& options);

}  // namespace lgh::bench
