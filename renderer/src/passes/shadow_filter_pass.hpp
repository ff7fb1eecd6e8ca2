// LGH shadow filter pass (GL compute): the shadow ratio of the LGH lighting, filtered.
//   inputs:  the shadow rays' visibility bits, the LGH's k samples per pixel (which slots hold a
//            light), G-buffer position and normal, camera
//   outputs: an R16F ratio texture (owned here) that the composite multiplies the LGH lighting by
//   shaders: glsl/shadow_ratio.comp (mean visibility of the k samples), then `iterations` passes
//            of glsl/shadow_atrous.comp (edge-avoiding a-trous wavelet, Dammertz et al. 2010)
#pragma once

#include "gl/gl_objects.hpp"
#include "passes/frame_targets.hpp"
#include "passes/shadow_ray_setup_pass.hpp"
#include "scene/camera.hpp"

namespace lgh {

struct ShadowFilterInputs {
  ShadowRayLayout layout;
  GLuint visibility = 0;
  GLuint lghSamples = 0;
  int iterations = 4;
};

class ShadowFilterPass {
 public:
  ShadowFilterPass();
  // Returns the texture holding the filtered ratio (valid until the next run or resize).
  GLuint run(const ShadowFilterInputs& inputs, const CameraMatrices& camera,
             const FrameTargets& frame);

 private:
  void resize(int width, int height);
  void ratio(const ShadowFilterInputs& inputs, const FrameTargets& frame, GLuint output);
  void atrous(int step, const CameraMatrices& camera, const FrameTargets& frame, GLuint input,
              GLuint output);

  gl::Program ratioProgram_;
  gl::Program atrousProgram_;
  gl::Texture ping_ = gl::Texture::empty();
  gl::Texture pong_ = gl::Texture::empty();
  int width_ = 0;
  int height_ = 0;
};

}  // namespace lgh
