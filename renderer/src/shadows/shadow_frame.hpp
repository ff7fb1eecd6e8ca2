// The shadows of one frame (docs/ARCHITECTURE.md "One frame", steps 4-6; docs/SHADOWS.md), after
// the LGH lighting (which picked k shadow samples per pixel) and the direct lighting:
//   inputs:  ShadowSettings, the frame's lights (buffer + count), the LGH's samples (when it
//            ran), the scene (its acceleration structures are built here on first use), the
//            G-buffer
//   outputs: visibility bits per pixel and ray (for the direct lighting), the filtered LGH shadow
//            ratio (for the composite), timing rows ("shadow ray setup", "shadow as build",
//            "shadow rays", "shadow transfer", "shadow filter") and decisions ("shadows",
//            "shadow_transport", "shadow_rays"), or a warning saying why the frame has no shadows.
// The Vulkan tracer belongs to the ShadowDevice; the GL side of its buffers (RayBatchTransport)
// and the GL passes belong here.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "frame_report.hpp"
#include "gl/gpu_timer.hpp"
#include "lgh/request.hpp"
#include "passes/frame_targets.hpp"
#include "passes/shadow_filter_pass.hpp"
#include "passes/shadow_ray_setup_pass.hpp"
#include "scene/camera.hpp"
#include "scene/scene_cache.hpp"
#include "shadows/ray_batch_transport.hpp"
#include "shadows/shadow_device.hpp"

namespace lgh {

struct ShadowFrameInputs {
  const ShadowSettings& settings;
  std::uint32_t seed = 1;
  GLuint lights = 0;  // SSBO of GpuLight
  int lightCount = 0;
  GLuint lghSamples = 0;  // SSBO of the LGH's samples; 0 when the frame has no LGH lighting
  int lghSampleCount = 0;
};

class ShadowFrame {
 public:
  // Traces in the tracer's ray lane `lane`: two ShadowFrames of different lanes may have their
  // traces in flight at once.
  ShadowFrame(ShadowDevice* device, vk::RayLane lane);
  ~ShadowFrame();
  ShadowFrame(const ShadowFrame&) = delete;
  ShadowFrame& operator=(const ShadowFrame&) = delete;

  // Hands the frame's shadow rays to Vulkan, or decides that it has none (settings off, no tracer
  // under auto, no rays). GL commands issued before awaitVisibility() run while Vulkan traces.
  // Throws lgh::Error: Unavailable when shadows are "on" without a tracer, Invalid for a tracing
  // path the device lacks, Internal for a Vulkan failure (the tracer is then reset and made again
  // by the next frame).
  void trace(const ShadowFrameInputs& inputs, const CachedScene& scene, const FrameTargets& frame,
             gl::GpuTimer& timer, FrameReport& report);
  // GL's next commands (the readers of visibility()) wait for the trace. No-op without one.
  void awaitVisibility();
  // Whether awaitVisibility() would return without the CPU waiting for Vulkan's trace.
  bool visibilityReady() const { return !awaiting_ || !transport_ || transport_->resultsReady(); }

  // The layout and visibility buffer the direct lighting reads (shadowedLights 0: unshadowed),
  // once awaitVisibility() has been called.
  const ShadowRayLayout& layout() const { return layout_; }
  GLuint visibility() const { return traced_ ? buffers_.visibility : 0; }
  bool traced() const { return traced_; }

  // The filtered LGH shadow ratio texture, 0 when the frame has no LGH shadows.
  GLuint filterLgh(int iterations, const CameraMatrices& camera, const FrameTargets& frame,
                   gl::GpuTimer& timer);

  // The shadowed brute-force reference's rays: from every pixel to each of `count` point lights
  // (PointLight SSBO, count <= vk::kMaxRaysPerPixel) from `first` on. Returns the visibility
  // buffer (bit r: light first + r), valid until the next trace. Throws like trace() when
  // shadows are off or cannot be traced.
  GLuint traceToPointLights(const ShadowSettings& settings, GLuint pointLights, int first,
                            int count, const CachedScene& scene, const FrameTargets& frame);

  // How rays reach Vulkan ("interop", "interop-finish", "staging"); "" before the first batch.
  std::string transportName() const { return transport_ ? transport_->name() : std::string(); }

  // Adds the writer of the Vulkan rows (acceleration structures, rays) and the CPU transfer row
  // to report.lateRows: the rays' GPU time is read when the frame is taken.
  void collectTimings(FrameReport& report);

 private:
  vk::ShadowTracer* tracerFor(const ShadowSettings& settings, FrameReport& report);
  vk::TracePath choosePath(vk::ShadowTracer& tracer, ShadowTracing requested) const;
  const vk::TraceScene& traceScene(vk::ShadowTracer& tracer, const CachedScene& scene);
  ShadowRayLayout budget(const ShadowFrameInputs& inputs, FrameReport& report) const;
  RayBatchTransport& transportFor(vk::ShadowTracer& tracer);
  void traceRays(const ShadowFrameInputs& inputs, vk::ShadowTracer& tracer, vk::TracePath path,
                 const CachedScene& scene, const FrameTargets& frame, gl::GpuTimer& timer,
                 FrameReport& report);

  ShadowDevice* device_;
  vk::RayLane lane_;
  std::unique_ptr<RayBatchTransport> transport_;
  bool awaiting_ = false;  // trace() handed rays over; awaitVisibility() has not been called
  std::uint64_t transportEpoch_ = 0;  // the ShadowDevice epoch transport_ belongs to
  ShadowRaySetupPass& setup();        // compiled by the first shadowed frame, not at start-up

  std::optional<ShadowRaySetupPass> setup_;
  std::optional<ShadowFilterPass> filter_;
  ShadowRayLayout layout_;
  RayBatchTransport::GlBuffers buffers_;
  GLuint lghSamples_ = 0;
  bool traced_ = false;
  std::function<double()> buildGpuMs_;  // set when this frame built the scene's structures
  double buildWallMs_ = -1.0;
  double transferMs_ = 0.0;
};

}  // namespace lgh
