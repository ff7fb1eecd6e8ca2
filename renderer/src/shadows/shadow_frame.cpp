#include "shadows/shadow_frame.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include "gl/slots.hpp"
#include "lgh/error.hpp"

namespace lgh {
namespace {

static_assert(vk::kRayTileSize == LGH_GROUP_2D, "the trace's tiles are the GL passes' work groups");

// Only the tiles that can show a surface have pixels with rays: the ray set-up gives every other
// pixel none, by its stores or by the clear before them.
vk::RayTiles rayTiles(const FrameTiles& tiles) {
  if (tiles.empty()) return {};
  return {.first = {static_cast<std::uint32_t>(tiles.first.x),
                    static_cast<std::uint32_t>(tiles.first.y)},
          .count = {static_cast<std::uint32_t>(tiles.count.x),
                    static_cast<std::uint32_t>(tiles.count.y)}};
}

// Rays start this far (relative to the scene's size) off their surface along its normal, and
// rays to a point end this fraction short of it (a VPL lies on a surface).
constexpr float kSurfaceOffset = 1e-4F;
constexpr float kEndEpsilon = 1e-3F;
// Direct-light jitter and the LGH's samples draw from different random streams.
constexpr std::uint32_t kDirectSeedSalt = 0x9e3779b9U;

float surfaceOffset(const Scene& scene) {
  const float size = scene.bounds.empty() ? 1.0F : glm::length(scene.bounds.size());
  return std::max(kSurfaceOffset * size, 1e-6F);
}

}  // namespace

ShadowFrame::ShadowFrame(ShadowDevice* device, vk::RayLane lane) : device_(device), lane_(lane) {}
ShadowFrame::~ShadowFrame() = default;

vk::ShadowTracer* ShadowFrame::tracerFor(const ShadowSettings& settings, FrameReport& report) {
  vk::ShadowTracer* tracer = device_ != nullptr ? device_->tracer() : nullptr;
  if (tracer != nullptr) return tracer;
  const std::string reason =
      device_ != nullptr ? device_->unavailableReason() : "this renderer traces no rays";
  if (settings.mode == ShadowMode::On) {
    throw Error(ErrorCode::Unavailable,
                "shadows were asked for, but this machine cannot trace them: " + reason,
                "/settings/shadows");
  }
  report.decide("shadows", "none");
  report.warn("rendered without shadows: " + reason);
  return nullptr;
}

vk::TracePath ShadowFrame::choosePath(vk::ShadowTracer& tracer, ShadowTracing requested) const {
  return chooseTracePath(tracer, requested);
}

ShadowRayLayout ShadowFrame::budget(const ShadowFrameInputs& inputs, FrameReport& report) const {
  ShadowRayLayout layout;
  layout.lightSamples = std::max(inputs.settings.lightSamples, 1);
  layout.lghSamples = inputs.lghSamples != 0 ? inputs.lghSampleCount : 0;
  const int capacity =
      (static_cast<int>(vk::kMaxRaysPerPixel) - layout.lghSamples) / layout.lightSamples;
  layout.shadowedLights = std::clamp(inputs.lightCount, 0, std::max(capacity, 0));
  if (layout.shadowedLights < inputs.lightCount) {
    report.warn(
        fmt::format("{} of {} lights cast no shadows: a pixel traces at most {} shadow "
                    "rays ({} per light, {} for the LGH's samples)",
                    inputs.lightCount - layout.shadowedLights, inputs.lightCount,
                    vk::kMaxRaysPerPixel, layout.lightSamples, layout.lghSamples));
  }
  return layout;
}

const vk::TraceScene& ShadowFrame::traceScene(vk::ShadowTracer& /*tracer*/,
                                              const CachedScene& scene) {
  return device_->traceScene(scene, &buildGpuMs_, &buildWallMs_);
}

void ShadowFrame::trace(const ShadowFrameInputs& inputs, const CachedScene& scene,
                        const FrameTargets& frame, gl::GpuTimer& timer, FrameReport& report) {
  // A frame that failed between its hand-over and its lighting left the wait unissued: issue it,
  // so that every semaphore Vulkan signals is waited on once.
  awaitVisibility();
  traced_ = false;
  buildGpuMs_ = {};
  buildWallMs_ = -1.0;
  transferMs_ = 0.0;
  layout_ = {};
  lghSamples_ = inputs.lghSamples;
  if (inputs.settings.mode == ShadowMode::Off) {
    report.decide("shadows", "off");
    return;
  }
  vk::ShadowTracer* tracer = tracerFor(inputs.settings, report);
  if (tracer == nullptr) return;
  const vk::TracePath path = choosePath(*tracer, inputs.settings.tracing);
  report.decide("shadows", std::string(enumName(path)));
  layout_ = budget(inputs, report);
  report.decide("shadow_rays", std::to_string(layout_.raysPerPixel()));
  if (layout_.raysPerPixel() == 0) return;
  try {
    traceRays(inputs, *tracer, path, scene, frame, timer, report);
  } catch (const Error& error) {
    transport_.reset();
    awaiting_ = false;
    if (device_ != nullptr) device_->reset(error.message());
    throw;
  }
}

void ShadowFrame::traceRays(const ShadowFrameInputs& inputs, vk::ShadowTracer& tracer,
                            vk::TracePath path, const CachedScene& scene, const FrameTargets& frame,
                            gl::GpuTimer& timer, FrameReport& report) {
  const vk::TraceScene& accel = traceScene(tracer, scene);
  RayBatchTransport& transport = transportFor(tracer);
  const vk::RayBatchShape shape{
      static_cast<std::uint32_t>(frame.width), static_cast<std::uint32_t>(frame.height),
      static_cast<std::uint32_t>(layout_.raysPerPixel()), rayTiles(frame.tilesWithSurfaces())};
  buffers_ = transport.prepare(shape);
  const float offset = surfaceOffset(scene.scene);
  {
    gl::ScopedGpuPass pass(timer, "shadow ray setup", gl::GpuWork::Compute);
    setup().run({layout_, inputs.lights, inputs.lghSamples, offset, inputs.seed ^ kDirectSeedSalt},
                frame, buffers_.origins, buffers_.targets);
  }
  vk::TraceParams params;
  params.tMin = offset;
  params.endEpsilon = kEndEpsilon;
  transferMs_ = transport.handOver(accel, path, shape, params);
  traced_ = true;
  awaiting_ = true;
  report.decide("shadow_transport", transport.name());
}

void ShadowFrame::awaitVisibility() {
  if (!awaiting_) return;
  awaiting_ = false;
  if (transport_) transport_->awaitResults();
}

ShadowRaySetupPass& ShadowFrame::setup() {
  if (!setup_) setup_.emplace();
  return *setup_;
}

RayBatchTransport& ShadowFrame::transportFor(vk::ShadowTracer& tracer) {
  if (!transport_ || transportEpoch_ != device_->epoch()) {
    transport_ = std::make_unique<RayBatchTransport>(tracer, lane_);
    transportEpoch_ = device_->epoch();
  }
  return *transport_;
}

GLuint ShadowFrame::traceToPointLights(const ShadowSettings& settings, GLuint pointLights,
                                       int first, int count, const CachedScene& scene,
                                       const FrameTargets& frame) {
  if (settings.mode == ShadowMode::Off) {
    throw Error(ErrorCode::Invalid, "a shadowed reference needs shadows", "/settings/shadows");
  }
  FrameReport ignored;
  ShadowSettings required = settings;
  required.mode = ShadowMode::On;
  vk::ShadowTracer* tracer = tracerFor(required, ignored);
  const vk::TracePath path = choosePath(*tracer, settings.tracing);
  try {
    const vk::TraceScene& accel = traceScene(*tracer, scene);
    RayBatchTransport& transport = transportFor(*tracer);
    const vk::RayBatchShape shape{static_cast<std::uint32_t>(frame.width),
                                  static_cast<std::uint32_t>(frame.height),
                                  static_cast<std::uint32_t>(count)};
    const RayBatchTransport::GlBuffers buffers = transport.prepare(shape);
    const float offset = surfaceOffset(scene.scene);
    setup().runToPointLights(pointLights, first, count, offset, frame, buffers.origins,
                             buffers.targets);
    vk::TraceParams params;
    params.tMin = offset;
    params.endEpsilon = kEndEpsilon;
    transport.trace(accel, path, shape, params);
    return buffers.visibility;
  } catch (const Error& error) {
    transport_.reset();
    if (device_ != nullptr) device_->reset(error.message());
    throw;
  }
}

GLuint ShadowFrame::filterLgh(int iterations, const CameraMatrices& camera,
                              const FrameTargets& frame, gl::GpuTimer& timer) {
  if (!traced_ || layout_.lghSamples == 0) return 0;
  if (!filter_) filter_.emplace();
  gl::ScopedGpuPass pass(timer, "shadow filter");
  return filter_->run({layout_, buffers_.visibility, lghSamples_, iterations}, camera, frame);
}

void ShadowFrame::collectTimings(FrameReport& report) {
  const bool traced = traced_ && device_ != nullptr && device_->tracer() != nullptr;
  const ShadowDevice::SubmissionMark mark =
      traced ? device_->mark() : ShadowDevice::SubmissionMark{};
  report.lateRows.push_back([device = device_, mark, traced, buildGpuMs = buildGpuMs_,
                             buildWallMs = buildWallMs_,
                             transferMs = transferMs_](TimingTable& table) {
    if (const std::optional<double> ms = readBuildGpuMs(buildGpuMs)) {
      table.add("shadow as build", TimingRow::Clock::Gpu, *ms);
    }
    // The build's wall time on the render thread: allocations and waits besides the GPU's work.
    if (buildWallMs >= 0.0) table.add("shadow as build wall", TimingRow::Clock::Cpu, buildWallMs);
    if (!traced) return;
    if (const std::optional<double> gpuMs = device->traceGpuMs(mark)) {
      table.add("shadow rays", TimingRow::Clock::Gpu, *gpuMs);
    }
    table.add("shadow transfer", TimingRow::Clock::Cpu, transferMs);
  });
}

}  // namespace lgh
