// The LGH construction benchmark behind `lgh-bench construct`: builds the Lighting Grid Hierarchy
// repeatedly from virtual point lights sampled on the built-in demo scene and reports per-step GPU
// times (medians of GL_TIMESTAMP queries), the level counts and the device - the paper's Tables 1
// and 2 on this machine's GPU.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "lgh/renderer.hpp"
#include "lgh/request.hpp"

namespace lgh {

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
  std::function<void(const std::string&)> progress;  // one line per finished run; may be empty
};

// Creates its own GL context (current on the calling thread while it runs). Returns
// {"benchmark", "device", "settings", "runs": [{"vpls", "method", "s1", "levels", "level_counts",
//  "grid_lights", "steps": [{"name", "median_ms", "min_ms", "max_ms"}], "total_ms", ...}]}.
// Throws lgh::Error (BadRequest for bad options, Unavailable without a context).
nlohmann::json runConstructBenchmark(const ConstructBenchmarkOptions& options);

}  // namespace lgh
