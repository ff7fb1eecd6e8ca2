#include "bench/result_json.hpp"

#include <cmath>
#include <string>

#include "lgh/enum_names.hpp"

namespace lgh::bench {

void to_json(nlohmann::json& j, const TimingStats& stats) {
  j = {{"name", stats.name},
       {"median_ms", stats.medianMs},
       {"min_ms", stats.minMs},
       {"max_ms", stats.maxMs}};
}

void to_json(nlohmann::json& j, const ConstructRun& run) {
  j = {{"vpls", run.vpls},
       {"method", std::string(enumName(run.method))},
       {"s1", run.binnedS1 ? "binned" : "direct"},
       {"levels", run.levels},
       {"fit_levels", run.fitLevels},
       {"atomics", run.fixedPointAtomics ? "fixed-point" : "float"},
       {"contributing_lights", run.contributingLights},
       {"level_counts", run.levelCounts},
       {"candidate_s1", run.candidateS1},
       {"grid_lights", run.gridLights},
       {"overflow", run.overflow},
       {"steps", run.steps},
       {"total_ms", run.totalMs},
       {"total_without_step_timers_ms", run.totalWithoutStepTimersMs},
       {"readback_ms", run.readbackMs},
       {"gpu_bytes", run.gpuBytes},
       {"vpl_sampling_cpu_ms", run.vplSamplingCpuMs}};
}

void to_json(nlohmann::json& j, const ConstructBenchmarkResult& result) {
  const ConstructBenchmarkOptions& o = result.options;
  nlohmann::json methods = nlohmann::json::array();
  for (LghSettings::Method method : o.methods) methods.push_back(std::string(enumName(method)));
  j = {{"benchmark", "lgh-construct"},
       {"device", result.device.toJson()},
       {"settings",
        {{"levels", o.levels == 0 ? nlohmann::json("auto") : nlohmann::json(o.levels)},
         {"methods", methods},
         {"warmup_iterations", o.warmupIterations},
         {"timed_iterations", o.timedIterations},
         {"per_level_timings", o.perLevelTimings},
         {"atomics", o.atomics},
         {"s1", o.s1},
         {"vpl_order", o.vplOrder},
         {"seed", o.seed},
         {"scene", result.scene}}},
       {"runs", result.runs}};
}

void to_json(nlohmann::json& j, const OverdrawStats& stats) {
  if (stats.pixels == 0) {
    j = {{"pixels", 0}};
    return;
  }
  nlohmann::json histogram = nlohmann::json::array();
  for (const OverdrawStats::Bin& bin : stats.histogram) {
    histogram.push_back({{"from", bin.from}, {"to", bin.to}, {"pixels", bin.pixels}});
  }
  j = {{"pixels", stats.pixels}, {"mean", stats.mean}, {"max", stats.max},
       {"p50", stats.p50},       {"p95", stats.p95},   {"histogram", histogram}};
}

void to_json(nlohmann::json& j, const RenderReference& reference) {
  j = {{"vpls", reference.vpls}, {"bruteforce_ms", reference.bruteforceMs}};
}

void to_json(nlohmann::json& j, const RenderRun& run) {
  j = {{"vpls", run.vpls},
       {"path", std::string(enumName(run.path))},
       {"interleave", std::string(enumName(run.interleave))},
       {"shadow_samples", run.shadowSamples},
       {"locked", run.locked},
       {"levels", run.levels},
       {"grid_lights", run.gridLights},
       {"passes", run.passes},
       {"build_ms", run.buildMs},
       {"lighting_ms", run.lightingMs},
       {"render_ms", run.renderMs}};
  if (run.overdraw) j["overdraw"] = *run.overdraw;
  if (run.error) {
    j["relative_rmse"] = run.error->relativeRmse;
    j["psnr"] =
        std::isfinite(run.error->psnr) ? nlohmann::json(run.error->psnr) : nlohmann::json("inf");
  }
}

void to_json(nlohmann::json& j, const RenderBenchmarkResult& result) {
  const RenderBenchmarkOptions& o = result.options;
  nlohmann::json paths = nlohmann::json::array();
  for (LightingPath path : o.paths) paths.push_back(std::string(enumName(path)));
  nlohmann::json interleaves = nlohmann::json::array();
  for (InterleaveMode mode : o.interleaves) interleaves.push_back(std::string(enumName(mode)));
  j = {{"benchmark", "lgh-render"},
       {"device", result.device.toJson()},
       {"settings",
        {{"width", o.width},
         {"height", o.height},
         {"vpls", o.vplCounts},
         {"paths", paths},
         {"interleaves", interleaves},
         {"shadow_samples", o.shadowSamples},
         {"alpha", o.alpha},
         {"locks", o.locks},
         {"warmup_seconds", o.warmupSeconds},
         {"warmup_iterations", o.warmupIterations},
         {"timed_iterations", o.timedIterations},
         {"seed", o.seed},
         {"vpl_intensity", o.vplIntensity},
         {"scene", result.scene}}},
       {"references", result.references},
       {"runs", result.runs}};
}

void to_json(nlohmann::json& j, const ShadowRun& run) {
  j = {{"path", std::string(enumName(run.path))},
       {"shadow_samples", run.shadowSamples},
       {"rays_per_pixel", run.raysPerPixel},
       {"transport", run.transport},
       {"passes", run.passes},
       {"rays_ms", run.raysMs},
       {"filter_ms", run.filterMs},
       {"rays_plus_filter_ms", run.raysMs + run.filterMs},
       {"frame_gpu_ms", run.frameGpuMs},
       {"rays_per_second", run.raysPerSecond}};
}

void to_json(nlohmann::json& j, const ShadowBuild& build) {
  j = {{"scene", build.scene}, {"triangles", build.triangles}, {"build", build.build}};
}

void to_json(nlohmann::json& j, const ShadowBenchmarkResult& result) {
  const ShadowBenchmarkOptions& o = result.options;
  j = {{"benchmark", "lgh-shadows"},
       {"device", result.device.toJson()},
       {"shadows", result.shadows.toJson()},
       {"settings",
        {{"width", o.width},
         {"height", o.height},
         {"vpls", o.vpls},
         {"shadow_samples", o.shadowSamples},
         {"filter_iterations", o.filterIterations},
         {"warmup_iterations", o.warmupIterations},
         {"warmup_seconds", o.warmupSeconds},
         {"timed_iterations", o.timedIterations},
         {"build_triangles", o.buildTriangles},
         {"build_iterations", o.buildIterations}}},
       {"runs", result.runs},
       {"builds", result.builds}};
}

void to_json(nlohmann::json& j, const HandoffBenchmarkResult& result) {
  j = {{"benchmark", "lgh-handoff"},
       {"device", result.device.toJson()},
       {"shadows", result.shadows.toJson()},
       {"transport", result.transport},
       {"settings",
        {{"iterations", result.options.iterations},
         {"warmup_iterations", result.options.warmupIterations}}},
       {"in_process_batch", result.inProcessBatch},
       {"socket_round_trip", result.socketRoundTrip},
       {"fd_passing", result.fdPassing}};
}

}  // namespace lgh::bench
