// Direct lighting pass.
//   inputs:  FrameTargets::gbuffer, the scene's analytic lights, camera position, ambient term
//   outputs: FrameTargets::direct (HDR radiance, alpha = coverage)
//   shaders: glsl/fullscreen.vert, glsl/direct_lighting.frag (BRDF: glsl/include/brdf.glsl)
#pragma once

#include <vector>

#include "gl/gl_objects.hpp"
#include "lgh/request.hpp"
#include "passes/frame_targets.hpp"
#include "scene/camera.hpp"

namespace lgh {

// Binds the G-buffer textures to units 0..4 as include/gbuffer.glsl expects.
void bindGBuffer(const GBufferTargets& gbuffer);

class DirectLightingPass {
 public:
  DirectLightingPass();
  void run(const std::vector<LightDesc>& lights, const CameraMatrices& camera, float ambient,
           FrameTargets& targets);

 private:
  gl::Program program_;
  gl::VertexArray emptyVertexArray_;
  gl::SizedBuffer lightBuffer_;
};

}  // namespace lgh
