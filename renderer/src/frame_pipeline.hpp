// The order of one frame's passes (docs/ARCHITECTURE.md, "One frame"): G-buffer -> [VPLs (random
// on surfaces, or light paths: settings.gi) + LGH build + LGH lighting into the indirect target,
// picking k shadow samples per pixel] -> shadow
// rays (GL setup, Vulkan trace) -> direct lighting with visibility -> [LGH shadow ratio +
// filter] -> composite (display codes for PNG, linear light for EXR) -> pack into a read-back
// buffer; with blended surfaces: composite in linear light -> forward pass of blended surfaces ->
// display pass -> pack. Owns the passes and two frame sets (targets, light buffer, shadow-ray
// lane): a shadowed frame's draw may stop after handing its rays to Vulkan (drawUntilShadows), so
// that the next frame's G-buffer runs on GL while Vulkan traces (docs/SHADOWS.md, "Overlapped
// frames"). The renderer owns the context, the scene cache, the read-back buffers and the frames
// in flight. The LGH part
// (passes/lgh_frame_lighting.hpp) is created on the first frame that enables it, so frames without
// it run exactly as before.
#pragma once

#include <array>
#include <memory>
#include <optional>

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

// The passes left of a frame that drawUntilShadows() stopped after its rays' hand-over: the
// direct lighting and the composite, which read nothing of the scene.
struct RemainingPasses {
  int set = 0;  // the frame set its first half drew into
  CameraMatrices camera;
  int lightCount = 0;
  float ambient = 0.0F;
  BrdfFeatures brdf;
  bool emission = false;
  OutputSettings output;
  OutputPixels pixels = OutputPixels::Display8;
};

class FramePipeline {
 public:
  static constexpr int kFrameSets = 2;

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
  // draw() into frame set `set`, stopping after the shadow rays' hand-over when what is left are
  // the direct lighting and the composite (no LGH, no blended surfaces, rays traced, at most
  // kMaxSplitPixels): those are returned, for finishDraw() after the next frame's first half.
  // Otherwise the whole frame is issued and nullopt returned.
  std::optional<RemainingPasses> drawUntilShadows(const RenderRequest& request,
                                                  const CachedScene& scene, gl::GpuTimer& timer,
                                                  FrameReport& report, OutputPixels pixels,
                                                  int set);
  void finishDraw(const RemainingPasses& remaining, gl::GpuTimer& timer);
  // Whether finishDraw() would issue its passes without the CPU waiting for the frame's rays
  // (always where GL waits for Vulkan on the GPU).
  bool finishReady(const RemainingPasses& remaining) {
    return frameSet(remaining.set).shadows.visibilityReady();
  }
  // Frames larger than this are drawn whole: a second set of their targets costs more memory
  // than the overlap saves time (their own passes keep the GPU busy).
  static constexpr long kMaxSplitPixels = 1280L * 720L;

  // Issues the copy of frame set `set`'s output into `packBuffer` as `layout`, timed as the GPU
  // pass "readback".
  void pack(OutputPixels pixels, FramePixels::Layout layout, GLuint packBuffer, gl::GpuTimer& timer,
            int set = 0);
  // The size of the pack buffer pack() needs for `pixels`.
  static std::size_t packBufferBytes(const FramePixels& pixels) {
    return PixelPackPass::bufferBytes(pixels);
  }

  // draw() of linear float output, read back at once into report.image, the timer read: the
  // synchronous frame of the tests and of the LGH benchmark's probes.
  void render(const RenderRequest& request, const CachedScene& scene, gl::GpuTimer& timer,
              FrameReport& report, LghFrameProbe* probe = nullptr);

 private:
  // One frame's targets, lights and shadow-ray lane.
  struct FrameSet {
    FrameSet(ShadowDevice* device, vk::RayLane lane) : shadows(device, lane) {}
    FrameTargets targets;
    gl::SizedBuffer lightBuffer;
    ShadowFrame shadows;
  };

  std::optional<RemainingPasses> drawInto(FrameSet& set, const RenderRequest& request,
                                          const CachedScene& scene, gl::GpuTimer& timer,
                                          FrameReport& report, OutputPixels pixels, bool maySplit,
                                          LghFrameProbe* probe);
  // `toOutput`: the frame has nothing to composite, and the pass writes its output.
  void directLighting(FrameSet& set, const RemainingPasses& remaining, gl::GpuTimer& timer,
                      bool toOutput);
  static void reportScene(const CachedScene& scene, FrameReport& report);
  // The probe's shadowed reference traces its rays here; its outputs that need the shadows.
  void prepareProbe(const RenderRequest& request, const CachedScene& scene, LghFrameProbe& probe);
  void finishProbe(GLuint shadowRatio, const CameraMatrices& camera, LghFrameProbe& probe) const;
  FrameSet& frameSet(int set);

 private:
  std::array<std::unique_ptr<FrameSet>, kFrameSets> sets_;
  FrameTargets& targets_;  // set 0's: whole frames, probes
  ShadowFrame& shadows_;   // set 0's
  GBufferPass gbufferPass_;
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
