// The LGH construction benchmark behind `lgh-bench construct`: builds the Lighting Grid Hierarchy
// repeatedly from virtual point lights sampled on the built-in demo scene and reports per-step GPU
// times (medians of GL_TIMESTAMP queries), the level counts and the device - the paper's Tables 1
// and 2 on this machine's GPU. The result is typed; lgh-bench prints it: the table and progress
// lines in server/bench/construct.cpp, the JSON of `--json` in server/bench/result_json.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "lgh/bench/statistics.hpp"
#include "lgh/device_info.hpp"
#include "lgh/renderer_options.hpp"
#include "lgh/request.hpp"

namespace lgh::bench {

struct ConstructRun;

struct ConstructBenchmarkOptions {
  std::vector<int> vplCounts{1000, 10000, 100000, 1000000};
  std::vector<LghSettings::Method> methods{LghSettings::Method::Gather};
  int levels = 0;  // 0: auto (largest L with |S1| < N/2)
  int warmupIterations = 2;
  int timedIterations = 10;
  bool perLevelTimings = false;  // gather: one dispatch and timer row per level (Table 1 rows)
  std::string atomics = "auto";  // "auto", "float" (GL_NV_shader_atomic_float), "fixed"
  // S1 accumulation: "auto" (binned from lgh::kLghBinnedMinLights lights on), "direct" (one
  // thread per light, global atomics), "binned" (by S1 tile, summed in shared memory), or "both"
  // (a run of each per count and method).
  std::string s1 = "auto";
  RendererOptions renderer;  // context backend and GPU
  std::uint32_t seed = 1;
  float totalFlux = 10.0F;
  // "random" (as sampled) or "morton" (sorted along a Z-order curve first): how the S1 scatter's
  // atomics fare with and without spatial coherence in the input.
  std::string vplOrder = "random";
  std::function<void(const ConstructRun&)> progress;  // called per finished run; may be empty
};

// One build configuration: a VPL count, a method and an S1 path.
struct ConstructRun {
  int vpls = 0;
  LghSettings::Method method = LghSettings::Method::Gather;
  bool binnedS1 = false;          // the S1 path that ran: binned, or direct
  double vplSamplingCpuMs = 0.0;  // sampling the VPLs on the scene (CPU)
  // The hierarchy built (read back after the timed builds).
  int levels = 0;
  int fitLevels = 0;
  bool fixedPointAtomics = false;  // the atomics that ran: fixed point, or float
  std::uint32_t contributingLights = 0;
  std::vector<std::uint32_t> levelCounts;  // |S_l|, levelCounts[l - 1]
  std::vector<std::uint32_t> candidateS1;  // auto levels: |S1| for L = index + 1
  std::uint32_t gridLights = 0;
  bool overflow = false;
  std::size_t gpuBytes = 0;  // the builder's GPU buffers
  // Timings [ms]: the builder's steps (levels beyond the top left out), the whole build with the
  // step timers and without them (medians), and the level table's read-back (CPU).
  std::vector<TimingStats> steps;
  double totalMs = 0.0;
  double totalWithoutStepTimersMs = 0.0;
  double readbackMs = 0.0;
};

struct ConstructBenchmarkResult {
  DeviceInfo device;
  ConstructBenchmarkOptions options;  // the settings it ran with
  std::string scene = "demo";
  std::vector<ConstructRun> runs;  // per VPL count, method and S1 path, in that nesting
};

// Creates its own GL context (current on the calling thread while it runs). Throws lgh::Error
// (BadRequest for bad options, Unavailable without a context).
ConstructBenchmarkResult runConstructBenchmark(const ConstructBenchmarkOptions& options);

}  // namespace lgh::bench
