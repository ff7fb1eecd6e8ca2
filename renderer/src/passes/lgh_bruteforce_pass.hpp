// Brute-force reference of the many-light lighting, for tests and the benchmark.
//   inputs:  the input point lights (PointLight SSBO), the level table (h_1 of the singularity
//            clamp), FrameTargets::gbuffer, camera
//   outputs: its own RGBA32F image of the frame: every light evaluated at every pixel with the
//            hierarchy's shading code, unshadowed; alpha = coverage
//   shaders: glsl/lgh_bruteforce.comp
#pragma once

#include "gl/gl_objects.hpp"
#include "lgh/image.hpp"
#include "passes/frame_targets.hpp"
#include "passes/lgh_lighting_common.hpp"
#include "scene/camera.hpp"

namespace lgh {

class LghBruteForcePass {
 public:
  void run(GLuint pointLights, int count, GLuint levels, const CameraMatrices& camera,
           const FrameTargets& frame);
  // The last run's image (waits for the GPU).
  FloatImage read() const;

 private:
  ProgramCache program_;
  gl::Texture output_{GL_TEXTURE_2D};
  int width_ = 0;
  int height_ = 0;
};

}  // namespace lgh
