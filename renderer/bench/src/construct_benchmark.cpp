#include "lgh/bench/construct_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include <fmt/format.h>

#include "context/gl_context.hpp"
#include "gl/gpu_timer.hpp"
#include "lgh/error.hpp"
#include "lightgrid/lgh_builder.hpp"
#include "lightgrid/vpl_sampler.hpp"
#include "scene/demo_scene.hpp"

namespace lgh::bench {
namespace {

constexpr const char* kTotalPass = "lgh build";

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

LghAtomics parseAtomics(const std::string& name) {
  if (name == "auto") return LghAtomics::Auto;
  if (name == "float") return LghAtomics::Float;
  if (name == "fixed") return LghAtomics::FixedPoint;
  throw Error(ErrorCode::BadRequest, "atomics must be auto, float or fixed, not '" + name + "'",
              "atomics");
}

// The S1 settings a run list covers ("both": direct, then binned).
std::vector<LghS1Scatter> parseS1(const std::string& name) {
  if (name == "auto") return {LghS1Scatter::Auto};
  if (name == "direct") return {LghS1Scatter::Direct};
  if (name == "binned") return {LghS1Scatter::Binned};
  if (name == "both") return {LghS1Scatter::Direct, LghS1Scatter::Binned};
  throw Error(ErrorCode::BadRequest, "s1 must be auto, direct, binned or both, not '" + name + "'",
              "s1");
}

// 30-bit Morton code of p in the box [lo, hi].
std::uint32_t mortonCode(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
  const glm::vec3 t = glm::clamp((p - lo) / glm::max(hi - lo, glm::vec3(1e-20F)), 0.0F, 1.0F);
  std::uint32_t code = 0;
  for (int bit = 9; bit >= 0; --bit) {
    for (int axis = 0; axis < 3; ++axis) {
      const auto q = static_cast<std::uint32_t>(t[axis] * 1023.0F);
      code = (code << 1) | ((q >> bit) & 1U);
    }
  }
  return code;
}

void sortAlongZOrder(std::vector<PointLight>& lights) {
  glm::vec3 lo(3e38F);
  glm::vec3 hi(-3e38F);
  for (const PointLight& light : lights) {
    lo = glm::min(lo, glm::vec3(light.positionPad));
    hi = glm::max(hi, glm::vec3(light.positionPad));
  }
  std::vector<std::pair<std::uint32_t, std::size_t>> keys;
  keys.reserve(lights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) {
    keys.emplace_back(mortonCode(glm::vec3(lights[i].positionPad), lo, hi), i);
  }
  std::sort(keys.begin(), keys.end());
  std::vector<PointLight> sorted;
  sorted.reserve(lights.size());
  for (const auto& key : keys) sorted.push_back(lights[key.second]);
  lights.swap(sorted);
}

void checkOptions(const ConstructBenchmarkOptions& options) {
  if (options.vplOrder != "random" && options.vplOrder != "morton") {
    throw Error(ErrorCode::BadRequest, "VPL order must be random or morton", "vpl_order");
  }
  if (options.vplCounts.empty() || options.methods.empty()) {
    throw Error(ErrorCode::BadRequest, "give at least one VPL count and one method");
  }
  for (int count : options.vplCounts) {
    if (count <= 0) {
      throw Error(ErrorCode::BadRequest, fmt::format("VPL count {} must be > 0", count), "vpls");
    }
  }
  if (options.timedIterations <= 0 || options.warmupIterations < 0) {
    throw Error(ErrorCode::BadRequest, "iterations must be > 0 and warm-up >= 0", "iterations");
  }
  if (options.levels < 0 || options.levels > kLghMaxLevels) {
    throw Error(ErrorCode::BadRequest, fmt::format("levels must be 0 (auto) .. {}", kLghMaxLevels),
                "levels");
  }
}

// A "lgh S<l>" row for a level the build did not have (auto levels: the CPU issues dispatches for
// every possible level, the ones past L are empty).
bool beyondTop(const std::string& step, int levelCount) {
  int level = 0;
  return std::sscanf(step.c_str(), "lgh S%d", &level) == 1 &&
         step.find_first_of(" +", 5) == std::string::npos && level > levelCount;
}

// Times `options.timedIterations` builds step by step, then as many as a whole; fills the run's
// hierarchy and timing fields.
void timedRun(LghBuilder& builder, GLuint lights, int count, const LghBuildSettings& settings,
              const ConstructBenchmarkOptions& options, ConstructRun& run) {
  for (int i = 0; i < options.warmupIterations; ++i) builder.build(lights, count, settings);
  glFinish();
  TimingSamples samples;
  for (int i = 0; i < options.timedIterations; ++i) {
    gl::GpuTimer timer;
    {
      gl::ScopedGpuPass total(timer, kTotalPass);
      builder.build(lights, count, settings, &timer);
    }
    TimingTable table;
    timer.collect(table);
    for (const TimingRow& row : table.rows) samples.add(row.name, row.milliseconds);
  }
  // The same builds timed as a whole only: per-step timestamp queries cost a few us each.
  std::vector<double> totals;
  for (int i = 0; i < options.timedIterations; ++i) {
    gl::GpuTimer timer;
    {
      gl::ScopedGpuPass total(timer, kTotalPass);
      builder.build(lights, count, settings);
    }
    TimingTable table;
    timer.collect(table);
    totals.push_back(table.get(kTotalPass));
  }
  const auto readStart = std::chrono::steady_clock::now();
  const LghLevelTable levels = builder.readLevels();
  run.readbackMs = msSince(readStart);

  for (const std::string& name : samples.names()) {
    if (name == kTotalPass || beyondTop(name, levels.levelCount)) continue;
    run.steps.push_back(samples.stats(name));
  }
  run.levels = levels.levelCount;
  run.fitLevels = levels.fitLevels;
  run.fixedPointAtomics = levels.fixedPoint;
  run.contributingLights = levels.contributingCount;
  for (const LghLevelInfo& level : levels.levels) run.levelCounts.push_back(level.count);
  run.candidateS1 = levels.candidateS1;
  run.gridLights = levels.totalLights;
  run.overflow = levels.overflow;
  run.totalMs = samples.median(kTotalPass);
  run.totalWithoutStepTimersMs = median(totals);
  run.gpuBytes = builder.allocatedBytes();
}

}  // namespace

ConstructBenchmarkResult runConstructBenchmark(const ConstructBenchmarkOptions& options) {
  checkOptions(options);
  const LghAtomics atomics = parseAtomics(options.atomics);
  const std::vector<LghS1Scatter> s1Modes = parseS1(options.s1);
  std::unique_ptr<GlContext> context = GlContext::create(options.renderer);
  const Scene scene = makeDemoScene();
  LghBuilder builder;
  gl::SizedBuffer lightBuffer;
  ConstructBenchmarkResult result;
  result.options = options;
  result.options.progress = nullptr;
  for (int count : options.vplCounts) {
    const auto sampleStart = std::chrono::steady_clock::now();
    std::vector<PointLight> vpls =
        sampleSurfaceVpls(scene, {count, options.seed, options.totalFlux});
    const double sampleMs = msSince(sampleStart);
    if (options.vplOrder == "morton") sortAlongZOrder(vpls);
    uploadPointLights(vpls, lightBuffer);
    for (LghSettings::Method method : options.methods) {
      for (LghS1Scatter s1 : s1Modes) {
        LghBuildSettings settings;
        settings.levels = options.levels;
        settings.method = method;
        settings.atomics = atomics;
        settings.s1 = s1;
        settings.splitLevels = options.perLevelTimings;
        ConstructRun run;
        run.vpls = count;
        run.method = method;
        run.binnedS1 = lghUseBinnedS1(settings, count);
        run.vplSamplingCpuMs = sampleMs;
        timedRun(builder, lightBuffer.id(), count, settings, options, run);
        if (options.progress) options.progress(run);
        result.runs.push_back(std::move(run));
      }
    }
  }
  result.device = context->info();
  return result;
}

}  // namespace lgh::bench
