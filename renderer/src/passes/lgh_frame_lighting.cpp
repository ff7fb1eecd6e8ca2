#include "passes/lgh_frame_lighting.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "gl/software_rasterizer.hpp"
#include "lightgrid/vpl_sampler.hpp"

namespace lgh {
namespace {

constexpr const char* kProbePass = "lgh path probe";

// The level table through a staging copy (see readShadowSamples).
LghLevelTable readLevelTable(GLuint levels) {
  gl::Buffer staging;
  glNamedBufferStorage(staging.id(), sizeof(LghLevelTableGpu), nullptr, GL_MAP_READ_BIT);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glCopyNamedBufferSubData(levels, staging.id(), 0, 0, sizeof(LghLevelTableGpu));
  LghLevelTableGpu table;
  glGetNamedBufferSubData(staging.id(), 0, sizeof(table), &table);
  return LghLevelTable::fromGpu(table);
}

void clearIndirect(FrameTargets& frame) {
  const float zero[4] = {0.0F, 0.0F, 0.0F, 0.0F};
  glClearTexImage(frame.indirect.id(), 0, GL_RGBA, GL_FLOAT, zero);
}

}  // namespace

LghFrameLighting::LghFrameLighting() = default;
LghFrameLighting::~LghFrameLighting() = default;

float LghFrameLighting::vplTotalIntensity(const Scene& scene, float vplIntensity) {
  if (scene.bounds.empty()) return vplIntensity;
  const float radius = 0.5F * glm::length(scene.bounds.size());
  return vplIntensity * std::max(radius * radius, 1e-12F);
}

void LghFrameLighting::uploadVpls(const LghSettings& settings, const CachedScene& cached) {
  vplCount_ = settings.vplCount;
  const VplKey key{
      &cached,           cached.scene.name, cached.scene.triangleCount(),
      settings.vplCount, settings.seed,     vplTotalIntensity(cached.scene, settings.vplIntensity)};
  if (vplKey_ == key) return;
  const std::vector<PointLight> vpls =
      sampleSurfaceVpls(cached.scene, {settings.vplCount, settings.seed, key.flux});
  uploadPointLights(vpls, vplBuffer_);
  vplKey_ = key;
}

void LghFrameLighting::traceVpls(const LghGiInputs& gi, const CachedScene& cached,
                                 gl::GpuTimer& timer, FrameReport& report) {
  if (!vplTracer_) vplTracer_ = std::make_unique<VplTracer>();
  vplKey_.reset();  // the buffer no longer holds the surface VPLs
  giTracing_ = &gi.tracer;
  vplLayout_ =
      vplTracer_->generate({gi.settings, gi.lights, gi.lightBuffer, gi.tracing, gi.materials},
                           cached, gi.tracer, vplBuffer_, timer, report);
  vplCount_ = vplLayout_.count;
}

void LghFrameLighting::collectTimings(FrameReport& report) {
  if (vplTracer_ && giTracing_ != nullptr) vplTracer_->collectTimings(*giTracing_, report);
  giTracing_ = nullptr;
}

void LghFrameLighting::run(const LghSettings& settings, const CachedScene& cached,
                           const CameraMatrices& camera, const BrdfFeatures& brdf,
                           FrameTargets& frame, gl::GpuTimer& timer, FrameReport& report,
                           LghFrameProbe* probe, const LghGiInputs* gi) {
  sampled_ = false;
  giTracing_ = nullptr;
  vplLayout_ = {};
  const bool lightPaths = gi != nullptr && gi->settings.enabled;
  report.decide("vpl_source", lightPaths ? "light-paths" : "surface");
  report.decide("vpls", std::to_string(lightPaths ? gi->settings.vplCount : settings.vplCount));
  report.decide("interleave", std::string(enumName(settings.interleave)));
  if (!lightPaths && settings.vplCount <= 0) {
    clearIndirect(frame);
    report.decide("lgh_lighting", "none");
    report.warn("LGH lighting enabled with vpl_count 0: no indirect light");
    return;
  }
  if (lightPaths) {
    traceVpls(*gi, cached, timer, report);
  } else {
    uploadVpls(settings, cached);
  }
  {
    gl::ScopedGpuPass pass(timer, "lgh build");
    builder_.build(vplBuffer_.id(), vplCount_, LghBuildSettings::fromRequest(settings), &timer);
  }
  LghLightingParams params = LghLightingParams::fromSettings(settings);
  params.overdraw = probe != nullptr && probe->overdraw;
  params.brdf = probe != nullptr && probe->genericBrdf ? BrdfFeatures{} : brdf;
  targets_.resize(frame.width, frame.height, params.interleave, params.samples);
  const LightingPath path = choosePath(settings.path, params, camera, frame, report);
  light(path, params, camera, frame, timer);
  sampled_ = true;
  report.decide("lgh_lighting", std::string(enumName(path)));
  report.decide("lgh_shadow_samples", std::to_string(params.samples));
  report.decide("lgh_brdf", params.brdf.describe());
  if (path == LightingPath::Raster && params.locked) {
    const bool interlock = raster_.lockMode(true) == LghRasterLightingPass::LockMode::Interlock;
    report.decide("lgh_reservoir_lock", interlock ? "interlock" : "spin");
  } else {
    report.decide("lgh_reservoir_lock", path == LightingPath::Compute ? "owned" : "none");
  }
  if (probe != nullptr) {
    probe->path = path;
    probe->vplLayout = vplLayout_;
    readProbe(params, camera, frame, timer, *probe, cached, lightPaths ? gi : nullptr);
    if (probe->bruteForce) {
      report.decide("reference", probe->shadowedReference ? "brute-force-shadowed" : "brute-force");
    }
  }
}

LghFrameLighting::ShadowSamples LghFrameLighting::shadowSamples() const {
  if (!sampled_) return {};
  return {targets_.shadowSamples.id(), targets_.samples};
}

LightingPath LghFrameLighting::choosePath(LightingPath requested, const LghLightingParams& params,
                                          const CameraMatrices& camera, FrameTargets& frame,
                                          FrameReport& report) {
  if (requested != LightingPath::Auto) {
    report.decide("lgh_lighting_choice", "configured");
    return requested;
  }
  if (gl::softwareRasterizer()) {
    report.decide("lgh_lighting_choice", "rule");  // no meaningful GPU timers on llvmpipe
    return LightingPath::Compute;
  }
  if (!measuredPath_) {
    measuredPath_ = measureFasterPath(params, camera, frame);
    spdlog::info("LGH lighting: the {} path measured faster on this device",
                 std::string(enumName(*measuredPath_)));
  }
  report.decide("lgh_lighting_choice", "measured");
  return *measuredPath_;
}

// Times both paths on this frame (after a warm-up run each, which also compiles the programs).
LightingPath LghFrameLighting::measureFasterPath(const LghLightingParams& params,
                                                 const CameraMatrices& camera,
                                                 FrameTargets& frame) {
  auto timeOnce = [&](LightingPath path) {
    gl::GpuTimer probeTimer;
    gl::GpuTimer lightingTimer;
    {
      gl::ScopedGpuPass pass(probeTimer, kProbePass);
      light(path, params, camera, frame, lightingTimer);
    }
    TimingTable table;
    probeTimer.collect(table);
    lightingTimer.discard();
    return table.get(kProbePass);
  };
  double best[2] = {0.0, 0.0};
  const LightingPath paths[2] = {LightingPath::Raster, LightingPath::Compute};
  for (int i = 0; i < 2; ++i) {
    timeOnce(paths[i]);
    best[i] = std::min(timeOnce(paths[i]), timeOnce(paths[i]));
  }
  spdlog::debug("LGH path probe: raster {:.3f} ms, compute {:.3f} ms", best[0], best[1]);
  return best[0] < best[1] ? LightingPath::Raster : LightingPath::Compute;
}

void LghFrameLighting::light(LightingPath path, const LghLightingParams& params,
                             const CameraMatrices& camera, FrameTargets& frame,
                             gl::GpuTimer& timer) {
  const LghHierarchyBuffers hierarchy{builder_.gridLights(), builder_.levels()};
  const bool interleaved = params.interleave > 1;
  if (path == LightingPath::Raster) {
    if (interleaved) {
      gl::ScopedGpuPass pass(timer, "lgh interleave split");
      interleave_.split(params, camera, frame, targets_);
    }
    gl::ScopedGpuPass pass(timer, "lgh lighting");
    raster_.run(hierarchy, params, camera, frame, targets_);
  } else {
    gl::ScopedGpuPass pass(timer, "lgh lighting");
    compute_.run(hierarchy, params, camera, frame, targets_);
  }
  if (interleaved) {
    gl::ScopedGpuPass pass(timer, "lgh interleave composite");
    interleave_.composite(params, camera, frame, targets_);
  }
}

void LghFrameLighting::readProbe(const LghLightingParams& params, const CameraMatrices& camera,
                                 FrameTargets& frame, gl::GpuTimer& timer, LghFrameProbe& probe,
                                 const CachedScene& scene, const LghGiInputs* gi) {
  if (probe.pathTracedSamples > 0 && gi != nullptr) {
    if (!pathTracer_) pathTracer_ = std::make_unique<PathTracedReference>();
    const PathTracingSettings settings{gi->settings.bounces, probe.pathTracedSamples,
                                       gi->settings.seed, gi->tracing};
    probe.pathTraced = pathTracer_->render(
        settings, {scene, gi->lights, gi->lightBuffer, camera, frame, gi->materials}, gi->tracer);
  }
  if (probe.bruteForce) {
    gl::ScopedGpuPass pass(timer, "lgh reference");
    const float minDistance = probe.referenceClamp == LghFrameProbe::ReferenceClamp::Hierarchy
                                  ? -1.0F
                                  : std::max(probe.referenceMinDistance, 0.0F);
    bruteForce_.run(vplBuffer_.id(), vplCount_, builder_.levels(), camera, frame, params.brdf,
                    probe.shadowedReference ? probe.visibility : PointLightVisibility{},
                    minDistance);
  }
  if (probe.readVpls) {
    probe.vpls.resize(static_cast<std::size_t>(vplCount_));
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(vplBuffer_.id(), 0,
                            static_cast<GLsizeiptr>(probe.vpls.size() * sizeof(PointLight)),
                            probe.vpls.data());
  }
  if (!probe.readBack) return;
  probe.indirect = readTextureImage(frame.indirect, frame.width, frame.height);
  if (probe.bruteForce) probe.reference = bruteForce_.read();
  probe.reservoirSums = readReservoirSums(targets_);
  probe.shadowSamples = readShadowSamples(targets_);
  probe.shadowSampleCount = targets_.samples;
  if (probe.overdraw) probe.overdrawCounts = readOverdraw(targets_);
  probe.levels = readLevelTable(builder_.levels());
}

}  // namespace lgh
