// The order of one frame's passes (docs/ARCHITECTURE.md, "One frame"): G-buffer -> [VPLs (random
// on surfaces, or light paths: settings.gi) + LGH build + LGH lighting into the indirect target,
// picking k shadow samples per pixel] -> shadow
// rays (GL setup, Vulkan trace) -> direct lighting with visibility -> [LGH shadow ratio +
// filter] -> composite (display codes for PNG, linear light for EXR) -> pack into a read-back
// buffer; with blended surfaces: composite in linear light -> forward pass of blended surfaces ->
// display pass -> pack. Owns the passes and the frame targets; the renderer owns the context, the
// scene cache, the read-back buffers and the frames in flight. The LGH part
// (passes/lgh_frame_lighting.hpp) is created on the first frame that enables it, so frames without
// it run exactly as before.
#pragma once

#include <memory>

#include "frame_report.hpp"
#include "gi/gi_tracing.hpp"
#include "gl/gpu_timer.hpp"
#include "passes/composite_pass.hpp"
#include "passes/direct_lighting_pass.hpp"
#include "passes/display_pass.hpp"
#include "passes/forward_blend_pass.hpp"
#include "passes/frame_targets.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/lgh_frame_lighting.hpp"
#include "passes/pixel_pack_pass.hpp"
#include "scene/scene_cache.hpp"
#include "shadows/shadow_frame.hpp"

namespace lgh {

class FramePipeline {
 public:
  // `shadowDevice`: where shadow rays are traced (nullptr: never; frames say so in a warning).
  explicit FramePipeline(ShadowDevice* shadowDevice = nullptr);
  ~FramePipeline();
  // `probe` (tests and the benchmark) asks an LGH frame for its intermediate results.
  // How the last shadowed frame handed its rays to Vulkan ("" before any).
  std::string shadowTransport() const { return shadows_.transportName(); }

  // Issues the frame's passes, the composite writing the output target for `pixels`; nothing is
  // read back and the GPU timer is not read (its rows come once the frame is done). The shadow
  // tracer's rows are written by report.lateRows when the frame is taken.
  void draw(const RenderRequest& request, const CachedScene& scene, gl::GpuTimer& timer,
            FrameReport& report, OutputPixels pixels, LghFrameProbe* probe = nullptr);
  // Issues the copy of the last frame's output into `packBuffer` as `layout`, timed as the GPU
  // pass "readback".
  void pack(OutputPixels pixels, FramePixels::Layout layout, GLuint packBuffer,
            gl::GpuTimer& timer);
  // The size of the pack buffer pack() needs for `pixels`.
  static std::size_t packBufferBytes(const FramePixels& pixels) {
    return PixelPackPass::bufferBytes(pixels);
  }

  // draw() of linear float output, read back at once into report.image, the timer read: the
  // synchronous frame of the tests and of the LGH benchmark's probes.
  void render(const RenderRequest& request, const CachedScene& scene, gl::GpuTimer& timer,
              FrameReport& report, LghFrameProbe* probe = nullptr);

 private:
  // The probe's shadowed reference traces its rays here; its outputs that need the shadows.
  void prepareProbe(const RenderRequest& request, const CachedScene& scene, LghFrameProbe& probe);
  void finishProbe(GLuint shadowRatio, const CameraMatrices& camera, LghFrameProbe& probe) const;

 private:
  FrameTargets targets_;
  gl::SizedBuffer lightBuffer_;
  GBufferPass gbufferPass_;
  ShadowFrame shadows_;
  GiTracing gi_;
  DirectLightingPass directLightingPass_;
  CompositePass compositePass_;
  ForwardBlendPass forwardBlendPass_;
  DisplayPass displayPass_;
  PixelPackPass pixelPackPass_;
  std::unique_ptr<LghFrameLighting> lghLighting_;
};

// The lights a frame uses: the asset's, the request's, and a default key + fill light when both
// are empty (recorded as a warning).
std::vector<LightDesc> frameLights(const RenderRequest& request, const Scene& scene,
                                   const CameraMatrices& camera,
                                   std::vector<std::string>& warnings);

}  // namespace lgh
