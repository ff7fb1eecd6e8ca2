#include "lgh/bench/gi_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "context/gl_context.hpp"
#include "frame_pipeline.hpp"
#include "gi_figures.hpp"
#include "lgh/error.hpp"
#include "lgh/testing/image_metrics.hpp"
#include "scene/scene_cache.hpp"
#include "shadows/shadow_device.hpp"

namespace lgh::bench {
namespace {

constexpr const char* kGenerationPass = "gi vpls";
constexpr const char* kBuildPass = "lgh build";
constexpr int kPanelWidth = 320;
// Untimed frames before the first timed one while warm-up frames are asked for (GPU clocks).
constexpr double kClockWarmupSeconds = 1.0;

// One frame configuration.
struct GiRun {
  int vpls = 0;
  int width = 0;
  int height = 0;
  bool shadows = true;
  int samples = 4;
  float alpha = 2.0F;
  InterleaveMode interleave = InterleaveMode::None;
};

// The medians of a configuration's timed frames.
struct TimedFrames {
  std::vector<TimingStats> passes;
  double frameMs = 0.0;
  double renderMs = 0.0;
  double median(const std::string& name) const {
    for (const TimingStats& pass : passes) {
      if (pass.name == name) return pass.medianMs;
    }
    return 0.0;
  }
};

void checkOptions(const GiBenchmarkOptions& o) {
  if (o.vplCounts.empty() || o.interleaves.empty()) {
    throw Error(ErrorCode::BadRequest, "give at least one VPL count and one interleaving");
  }
  for (int count : o.vplCounts) {
    if (count <= 0) throw Error(ErrorCode::BadRequest, "VPL counts must be > 0", "vpls");
  }
  if (o.width <= 0 || o.height <= 0 || o.timedIterations <= 0 || o.warmupIterations < 0 ||
      o.table3Vpls <= 0) {
    throw Error(ErrorCode::BadRequest, "sizes, VPL counts and iterations must be > 0");
  }
  if (o.bounces < 1 || o.bounces > 3) {
    throw Error(ErrorCode::BadRequest, "bounces must be 1..3", "bounces");
  }
  if (!(o.alpha > 0.0F)) throw Error(ErrorCode::BadRequest, "alpha must be > 0", "alpha");
  if (!(o.shadowJitter >= 0.0F && o.shadowJitter <= 1.0F)) {
    throw Error(ErrorCode::BadRequest, "the shadow jitter is 0..1", "shadow_jitter");
  }
  if (o.path == LightingPath::Auto) {
    throw Error(ErrorCode::BadRequest, "the lighting path is raster or compute", "path");
  }
  if (o.quality && (o.qualityWidth <= 0 || o.qualityHeight <= 0 || o.qualityVpls <= 0 ||
                    o.pathTracedSamples <= 0 || o.qualityAlphas.empty())) {
    throw Error(ErrorCode::BadRequest, "the quality runs need a size, VPLs, samples and alphas");
  }
}

GiError toGiError(const MaterialErrors& e) {
  return {.relativeRmse = e.all.relativeRmse,
          .psnr = e.all.psnr,
          .diffuseRelativeRmse = e.diffuse.relativeRmse,
          .glossyRelativeRmse = e.glossy.relativeRmse,
          .bias = e.bias,
          .diffuseBias = e.diffuseBias,
          .glossyBias = e.glossyBias,
          .glossyFraction = e.glossyFraction};
}

std::string countLabel(int count) {
  if (count >= 1000000 && count % 1000000 == 0) return fmt::format("{}M", count / 1000000);
  if (count >= 1000 && count % 1000 == 0) return fmt::format("{}K", count / 1000);
  return std::to_string(count);
}

class GiSession {
 public:
  explicit GiSession(const GiBenchmarkOptions& options)
      : options_(options),
        context_(GlContext::create(options.renderer)),
        cache_(options.renderer),
        scene_(cache_.get(options.scene).entry),
        pipeline_(&device_) {}

  const DeviceInfo& device() const { return context_->info(); }
  ShadowInfo shadows() { return device_.info(pipeline_.shadowTransport()); }
  std::size_t triangles() const { return scene_->scene.triangleCount(); }

  RenderRequest request(const GiRun& run) const {
    RenderRequest request;
    request.scene = options_.scene;
    request.output.width = run.width;
    request.output.height = run.height;
    request.settings.shadows.mode = run.shadows ? ShadowMode::On : ShadowMode::Off;
    request.settings.depthPrepass = options_.depthPrepass;
    LghSettings& lgh = request.settings.lgh;
    lgh.enabled = true;
    lgh.alpha = run.alpha;
    lgh.path = options_.path;
    lgh.interleave = run.interleave;
    lgh.shadowSamples = run.samples;
    lgh.shadowJitter = options_.shadowJitter;
    // The paper's locks: only for 4x4 interleaving, and only the raster path has them.
    lgh.lockedReservoir =
        options_.path == LightingPath::Raster && run.interleave == InterleaveMode::Tiles4x4;
    request.settings.gi = {
        .enabled = true, .bounces = options_.bounces, .vplCount = run.vpls, .seed = options_.seed};
    return request;
  }

  FrameReport frame(const RenderRequest& request, LghFrameProbe* probe = nullptr) {
    FrameReport report;
    gl::GpuTimer timer;
    pipeline_.render(request, *scene_, timer, report, probe);
    return report;
  }

  // Renders `run` untimed for `seconds` of wall time: the GPU's clocks ramp up before the first
  // timed frame (as lgh-bench render does; docs/BENCHMARKS.md).
  void warmUp(const GiRun& run, double seconds) {
    const RenderRequest req = request(run);
    const auto start = std::chrono::steady_clock::now();
    do {
      frame(req);
    } while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() <
             seconds);
  }

  TimedFrames time(const GiRun& run) {
    const RenderRequest req = request(run);
    for (int i = 0; i < options_.warmupIterations; ++i) frame(req);
    TimingSamples samples;
    std::vector<double> frames;
    std::vector<double> renders;
    for (int i = 0; i < options_.timedIterations; ++i) {
      const FrameReport report = frame(req);
      for (const TimingRow& row : report.timings.rows) samples.add(row.name, row.milliseconds);
      const double total = report.timings.gpuTotal();
      frames.push_back(total);
      renders.push_back(total - std::max(report.timings.get(kGenerationPass), 0.0) -
                        std::max(report.timings.get(kBuildPass), 0.0));
    }
    TimedFrames timed;
    for (const std::string& name : samples.names()) timed.passes.push_back(samples.stats(name));
    timed.frameMs = bench::median(frames);
    timed.renderMs = bench::median(renders);
    return timed;
  }

 private:
  // Destroyed in reverse: the frame's GL objects and the scene (with its acceleration structures)
  // before the Vulkan device, and that before the GL context.
  GiBenchmarkOptions options_;
  std::unique_ptr<GlContext> context_;
  ShadowDevice device_;
  SceneCache cache_;
  std::shared_ptr<CachedScene> scene_;
  FramePipeline pipeline_;
};

void progress(const GiBenchmarkOptions& o, const std::string& line) {
  if (o.progress) o.progress(line);
}

GiTable2Row table2Row(GiSession& session, const GiBenchmarkOptions& o, int vpls,
                      std::vector<HeatMapPanel>& panels) {
  GiTable2Row row;
  row.vpls = vpls;
  GiRun run{.vpls = vpls, .width = o.width, .height = o.height, .alpha = o.alpha};
  run.shadows = false;
  run.samples = 1;
  row.renderNoShadowMs = session.time(run).renderMs;
  run.shadows = true;
  row.render1ShadowMs = session.time(run).renderMs;
  run.samples = 4;
  const TimedFrames four = session.time(run);
  row.render4ShadowsMs = four.renderMs;
  row.frame4ShadowsMs = four.frameMs;
  row.generationMs = four.median(kGenerationPass);
  row.constructionMs = four.median(kBuildPass);
  row.passes = four.passes;
  LghFrameProbe probe;
  probe.overdraw = o.overdraw;
  probe.readVpls = true;
  const FrameReport report = session.frame(session.request(run), &probe);
  row.levels = probe.levels.levelCount;
  row.gridLights = probe.levels.totalLights;
  row.litVpls = static_cast<std::uint32_t>(
      std::count_if(probe.vpls.begin(), probe.vpls.end(), [](const PointLight& vpl) {
        return vpl.intensityPad.r + vpl.intensityPad.g + vpl.intensityPad.b > 0.0F;
      }));
  if (o.overdraw) {
    row.overdraw = overdrawStats(probe.overdrawCounts, probe.indirect);
    panels.push_back({fmt::format("{} VPLS, MEAN {:.0f}", countLabel(vpls), row.overdraw->mean),
                      report.image, std::move(probe.overdrawCounts)});
  }
  progress(o, fmt::format("gi table 2: {} VPLs: generation {:.3f} ms, construction {:.3f} ms, "
                          "render {:.3f} / {:.3f} / {:.3f} ms (no shadow / 1 / 4 samples)",
                          vpls, row.generationMs, row.constructionMs, row.renderNoShadowMs,
                          row.render1ShadowMs, row.render4ShadowsMs));
  return row;
}

// The targets hold for one configuration (docs/GI.md): 1280x720, 100K VPLs, 4 samples,
// alpha 2 (the paper's 1). Other configurations report no target rather than a misleading one.
double targetMsFor(const GiBenchmarkOptions& o, InterleaveMode interleave) {
  if (o.width != 1280 || o.height != 720 || o.table3Vpls != 100000 || o.alpha != 2.0F) return 0.0;
  if (interleave == InterleaveMode::None) return 15.0;
  if (interleave == InterleaveMode::Tiles4x4) return 8.0;
  return 0.0;
}

GiTable3Column table3Column(GiSession& session, const GiBenchmarkOptions& o,
                            InterleaveMode interleave, Image8* frameImage) {
  const GiRun run{.vpls = o.table3Vpls,
                  .width = o.width,
                  .height = o.height,
                  .shadows = true,
                  .samples = 4,
                  .alpha = o.alpha,
                  .interleave = interleave};
  const TimedFrames timed = session.time(run);
  GiTable3Column column;
  column.interleave = interleave;
  column.passes = timed.passes;
  column.gbufferMs = timed.median("gbuffer");
  column.generationMs = timed.median(kGenerationPass);
  column.constructionMs = timed.median(kBuildPass);
  column.lightingMs = timed.median("lgh interleave split") + timed.median("lgh lighting") +
                      timed.median("lgh interleave composite");
  column.shadowRaysMs = timed.median("shadow ray setup") + timed.median("shadow rays");
  column.shadowFilterMs = timed.median("shadow filter");
  column.compositingMs = timed.median("direct lighting") + timed.median("composite");
  column.frameMs = timed.frameMs;
  column.renderMs = timed.renderMs;
  column.targetMs = targetMsFor(o, interleave);
  if (frameImage != nullptr) {
    const FrameReport report = session.frame(session.request(run));
    *frameImage = toDisplay8(report.image, ToneMap::Aces, 1.0F, false);
  }
  progress(o, fmt::format("gi table 3: {} VPLs, interleave {}: frame {:.3f} ms (lighting {:.3f}, "
                          "shadow rays {:.3f}, filter {:.3f})",
                          o.table3Vpls, enumName(interleave), column.frameMs, column.lightingMs,
                          column.shadowRaysMs, column.shadowFilterMs));
  return column;
}

GiQuality quality(GiSession& session, const GiBenchmarkOptions& o) {
  GiQuality result;
  result.width = o.qualityWidth;
  result.height = o.qualityHeight;
  result.vpls = o.qualityVpls;
  result.pathTracedSamples = o.pathTracedSamples;
  GiRun run{.vpls = o.qualityVpls,
            .width = o.qualityWidth,
            .height = o.qualityHeight,
            .alpha = o.qualityAlphas.front()};
  // The references: the shadowed brute force without a clamp and the path tracer; the unshadowed
  // brute force with the hierarchy's clamp and without one (the VPLs do not depend on alpha).
  LghFrameProbe references;
  references.bruteForce = true;
  references.shadowedReference = true;
  references.referenceClamp = LghFrameProbe::ReferenceClamp::Fixed;
  references.referenceMinDistance = 0.0F;
  references.pathTracedSamples = o.pathTracedSamples;
  const FrameReport referenceReport = session.frame(session.request(run), &references);
  result.bruteForceMs = referenceReport.timings.get("lgh reference");
  const auto& classes = references.metallicRoughness;
  result.vplsVsPathTracer =
      toGiError(compareByMaterial(references.reference, references.pathTraced, classes));
  progress(o, fmt::format("gi quality: references at {}x{}, {} VPLs: shadowed brute force "
                          "{:.1f} ms; its relative RMSE against the path tracer {:.4f}",
                          o.qualityWidth, o.qualityHeight, o.qualityVpls, result.bruteForceMs,
                          result.vplsVsPathTracer.relativeRmse));
  run.shadows = false;
  LghFrameProbe hierarchyClamp;
  hierarchyClamp.bruteForce = true;
  session.frame(session.request(run), &hierarchyClamp);
  LghFrameProbe noClamp;
  noClamp.bruteForce = true;
  noClamp.referenceClamp = LghFrameProbe::ReferenceClamp::Fixed;
  noClamp.referenceMinDistance = 0.0F;
  session.frame(session.request(run), &noClamp);
  run.shadows = true;
  for (const float alpha : o.qualityAlphas) {
    for (const InterleaveMode interleave : o.interleaves) {
      run.alpha = alpha;
      run.interleave = interleave;
      LghFrameProbe probe;
      session.frame(session.request(run), &probe);
      const FloatImage shadowed = multiplied(probe.indirect, probe.shadowRatio);
      GiQualityRun entry;
      entry.alpha = alpha;
      entry.interleave = interleave;
      entry.vsVplReference = toGiError(compareByMaterial(shadowed, references.reference, classes));
      entry.vsPathTracer = toGiError(compareByMaterial(shadowed, references.pathTraced, classes));
      entry.hierarchyOnly =
          toGiError(compareByMaterial(probe.indirect, hierarchyClamp.reference, classes));
      entry.hierarchyAndClamp =
          toGiError(compareByMaterial(probe.indirect, noClamp.reference, classes));
      progress(o, fmt::format("gi quality: alpha {}, interleave {}: relative RMSE {:.4f} against "
                              "the VPLs, {:.4f} against the path tracer",
                              alpha, enumName(interleave), entry.vsVplReference.relativeRmse,
                              entry.vsPathTracer.relativeRmse));
      result.runs.push_back(entry);
    }
  }
  return result;
}

}  // namespace

GiBenchmarkResult runGiBenchmark(const GiBenchmarkOptions& options) {
  checkOptions(options);
  GiSession session(options);
  GiBenchmarkResult result;
  result.options = options;
  result.options.progress = nullptr;
  result.device = session.device();
  result.sceneTriangles = session.triangles();
  if (options.warmupIterations > 0) {
    session.warmUp({.vpls = options.table3Vpls,
                    .width = options.width,
                    .height = options.height,
                    .shadows = true,
                    .samples = 4,
                    .alpha = options.alpha},
                   kClockWarmupSeconds);
  }
  std::vector<HeatMapPanel> panels;
  for (const int vpls : options.vplCounts) {
    result.table2.push_back(table2Row(session, options, vpls, panels));
  }
  result.shadows = session.shadows();
  const auto at = [&](int vpls) -> const GiTable2Row* {
    for (const GiTable2Row& row : result.table2) {
      if (row.vpls == vpls) return &row;
    }
    return nullptr;
  };
  const GiTable2Row* tenK = at(10000);
  if (tenK != nullptr && result.table2.back().vpls > 10000 && tenK->render4ShadowsMs > 0.0) {
    result.scalingRatio = result.table2.back().render4ShadowsMs / tenK->render4ShadowsMs;
  }
  for (const InterleaveMode interleave : options.interleaves) {
    Image8* frame = interleave == InterleaveMode::None ? &result.figures.frame : nullptr;
    result.table3.push_back(table3Column(session, options, interleave, frame));
  }
  if (options.quality) result.quality = quality(session, options);
  if (!panels.empty()) {
    result.figures.heatMaps = overdrawHeatMaps(panels, kPanelWidth);
    std::vector<PlotPoint> points;
    for (const GiTable2Row& row : result.table2) {
      if (row.overdraw) {
        points.push_back(
            {static_cast<double>(row.gridLights), row.overdraw->mean, countLabel(row.vpls)});
      }
    }
    result.figures.overdrawPlot =
        logLogPlot(points, "GRID LIGHTS", "MEAN LIGHTS EVALUATED PER PIXEL");
  }
  return result;
}

}  // namespace lgh::bench
