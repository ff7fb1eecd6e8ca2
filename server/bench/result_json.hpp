// The JSON documents of `lgh-bench ... --json`, from the benchmarks' typed results: one to_json
// per result struct (nlohmann's ADL hook, so `nlohmann::json(result)` works). The keys and their
// nesting are an interface: scripts/h100-run collects these documents and docs/BENCHMARKS.md
// quotes them.
#pragma once

#include <nlohmann/json.hpp>

#include "lgh/bench/construct_benchmark.hpp"
#include "lgh/bench/handoff_benchmark.hpp"
#include "lgh/bench/render_benchmark.hpp"
#include "lgh/bench/shadow_benchmark.hpp"
#include "lgh/bench/statistics.hpp"

namespace lgh::bench {

// {"name", "median_ms", "min_ms", "max_ms"}
void to_json(nlohmann::json& j, const TimingStats& stats);

// {"vpls", "method", "s1", "levels", "fit_levels", "atomics", "contributing_lights",
//  "level_counts", "candidate_s1", "grid_lights", "overflow", "steps": [TimingStats], "total_ms",
//  "total_without_step_timers_ms", "readback_ms", "gpu_bytes", "vpl_sampling_cpu_ms"}
void to_json(nlohmann::json& j, const ConstructRun& run);
// {"benchmark": "lgh-construct", "device", "settings", "runs": [ConstructRun]}
void to_json(nlohmann::json& j, const ConstructBenchmarkResult& result);

// {"pixels"} when nothing is covered, else {"pixels", "mean", "max", "p50", "p95",
//  "histogram": [{"from", "to", "pixels"}]}
void to_json(nlohmann::json& j, const OverdrawStats& stats);
// {"vpls", "bruteforce_ms"}
void to_json(nlohmann::json& j, const RenderReference& reference);
// {"vpls", "path", "interleave", "shadow_samples", "locked", "levels", "grid_lights",
//  "passes": [TimingStats], "build_ms", "lighting_ms", "render_ms", "relative_rmse", "psnr"
//  (a number, or "inf"), "overdraw"}; the last three only when measured
void to_json(nlohmann::json& j, const RenderRun& run);
// {"benchmark": "lgh-render", "device", "settings", "references": [RenderReference],
//  "runs": [RenderRun]}
void to_json(nlohmann::json& j, const RenderBenchmarkResult& result);

// {"path", "shadow_samples", "rays_per_pixel", "transport", "passes": [TimingStats], "rays_ms",
//  "filter_ms", "rays_plus_filter_ms", "frame_gpu_ms", "rays_per_second"}
void to_json(nlohmann::json& j, const ShadowRun& run);
// {"scene", "triangles", "build": TimingStats}
void to_json(nlohmann::json& j, const ShadowBuild& build);
// {"benchmark": "lgh-shadows", "device", "shadows", "settings", "runs": [ShadowRun],
//  "builds": [ShadowBuild]}
void to_json(nlohmann::json& j, const ShadowBenchmarkResult& result);

// {"benchmark": "lgh-handoff", "device", "shadows", "transport", "settings",
//  "in_process_batch", "socket_round_trip", "fd_passing": TimingStats}
void to_json(nlohmann::json& j, const HandoffBenchmarkResult& result);

}  // namespace lgh::bench
