// Direct lighting pass.
//   inputs:  FrameTargets::gbuffer, the frame's lights buffer, the shadow rays' visibility (the
//            first layout.shadowedLights lights are shadowed), camera position, ambient term
//   outputs: FrameTargets::direct (HDR radiance, alpha = coverage)
//   shaders: glsl/fullscreen.vert, glsl/direct_lighting.frag (BRDF: glsl/include/brdf.glsl)
#pragma once

#include <vector>

#include "gl/gl_objects.hpp"
#include "lgh/request.hpp"
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
};

class DirectLightingPass {
 public:
  DirectLightingPass();
  void run(const DirectLightingInputs& inputs, const CameraMatrices& camera, FrameTargets& targets);

 private:
  gl::Program program_;
  gl::VertexArray emptyVertexArray_;
};

}  // namespace lgh
