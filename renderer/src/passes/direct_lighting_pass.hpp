// Direct lighting pass.
//   inputs:  FrameTargets::gbuffer, the frame's lights buffer, the shadow rays' visibility (the
//            first layout.shadowedLights lights are shadowed), camera position, ambient term
//   outputs: FrameTargets::direct (HDR radiance, alpha = coverage); or, runToOutput (frames with
//            nothing to composite: no LGH lighting, no blended surfaces), the frame's output as
//            the composite pass writes it (passes/composite_pass.hpp), one full-screen pass less
//   shaders: glsl/direct_lighting.comp (BRDF: glsl/include/brdf.glsl), a compute pass compiled
//            for the frame's material models and layers (passes/brdf_features.hpp)
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>

#include "gl/gl_objects.hpp"
#include "gl/software_rasterizer.hpp"
#include "lgh/frame_pixels.hpp"
#include "lgh/request.hpp"
#include "passes/brdf_features.hpp"
#include "passes/frame_targets.hpp"
#include "passes/shadow_ray_setup_pass.hpp"
#include "scene/camera.hpp"

namespace lgh {

// Binds the G-buffer textures to units 0..4 as include/gbuffer.glsl expects.
void bindGBuffer(const GBufferTargets& gbuffer);

struct DirectLightingInputs {
  GLuint lights = 0;  // SSBO of GpuLight (passes/light_buffer.hpp)
  int lightCount = 0;
  ShadowRayLayout shadows;  // shadowedLights 0: unshadowed
  GLuint visibility = 0;    // the shadow rays' visibility bits (shadows.shadowedLights > 0)
  float ambient = 0.0F;
  BrdfFeatures brdf;     // the models and layers the G-buffer holds
  bool emission = true;  // the G-buffer's emissive target was written (surfacesEmit())
};

class DirectLightingPass {
 public:
  // `unrollsLightLoops` (passes/light_loops.hpp): as the device prefers (tests try both).
  explicit DirectLightingPass(bool unrollsLightLoops = gl::softwareRasterizer())
      : unrollsLightLoops_(unrollsLightLoops) {}
  void run(const DirectLightingInputs& inputs, const CameraMatrices& camera, FrameTargets& targets);
  void runToOutput(const DirectLightingInputs& inputs, const CameraMatrices& camera,
                   const OutputSettings& output, OutputPixels pixels, FrameTargets& targets);

 private:
  GLuint program(const DirectLightingInputs& inputs,
                 const std::optional<OutputPixels>& finalOutput);
  void dispatch(GLuint program, const DirectLightingInputs& inputs, const CameraMatrices& camera,
                FrameTargets& targets, const FrameTiles& tiles);

  // By their defines (BrdfFeatures::defines(), and the light counts where the loops unroll) and
  // the output written (none: FrameTargets::direct), built on first use.
  using ProgramKey = std::pair<std::string, std::optional<OutputPixels>>;
  std::map<ProgramKey, gl::Program> programs_;
  bool clearsBackground_ = gl::softwareRasterizer();  // bindFrameOutput's clearFirst
  bool unrollsLightLoops_;
};

}  // namespace lgh
