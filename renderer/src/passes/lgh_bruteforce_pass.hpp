// Brute-force reference of the many-light lighting, for tests and the benchmark.
//   inputs:  the input point lights (PointLight SSBO), the level table (h_1 of the hierarchy's
//            singularity clamp) or a clamp of its own, FrameTargets::gbuffer, camera; shadowed: a
//            tracer of rays to the lights
//   outputs: its own RGBA32F image of the frame: every light evaluated at every pixel with the
//            hierarchy's shading code, unshadowed or times the visibility of one ray per light
//            and pixel (ground truth for the shadowed frame); alpha = coverage
//   shaders: glsl/lgh_bruteforce.comp
#pragma once

#include <functional>

#include "gl/gl_objects.hpp"
#include "lgh/image.hpp"
#include "passes/frame_targets.hpp"
#include "passes/lgh_lighting_common.hpp"
#include "scene/camera.hpp"

namespace lgh {

// Traces a ray from every pixel to each of `count` point lights from `first` on (PointLight SSBO
// `pointLights`; count <= 64) and returns the visibility buffer (include/ray_batch.glsl layout:
// bit r of a pixel's words for light first + r).
using PointLightVisibility = std::function<GLuint(GLuint pointLights, int first, int count)>;

class LghBruteForcePass {
 public:
  // `visibility`: shadowed with its rays (in chunks of 64 lights), unshadowed when empty.
  // `minDistance`: the clamp's d_min in world units (0: none); < 0: the hierarchy's, h_1.
  // `brdf`: what the kernel's BRDF is compiled for, as the lighting passes'.
  void run(GLuint pointLights, int count, GLuint levels, const CameraMatrices& camera,
           const FrameTargets& frame, const BrdfFeatures& brdf,
           const PointLightVisibility& visibility = {}, float minDistance = -1.0F);
  // The last run's image (waits for the GPU).
  FloatImage read() const;

 private:
  void dispatch(GLuint program, GLuint pointLights, GLuint levels, const CameraMatrices& camera,
                const FrameTargets& frame);

  ProgramCache program_;
  gl::Texture output_{GL_TEXTURE_2D};
  int width_ = 0;
  int height_ = 0;
};

}  // namespace lgh
