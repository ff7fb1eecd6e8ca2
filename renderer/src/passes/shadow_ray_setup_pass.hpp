// Shadow ray setup pass (GL compute), the first step of a shadowed frame:
//   inputs:  G-buffer position and normal, the frame's lights buffer (the first `shadowedLights`
//            get `lightSamples` rays each), the LGH's k shadow samples per pixel (when it ran)
//   outputs: the ray batch's origins and targets (layout: vk/shadow_tracer.hpp)
//   shaders: glsl/shadow_ray_setup.comp (include/ray_batch.glsl)
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "gl/gl_objects.hpp"
#include "gl/software_rasterizer.hpp"
#include "passes/frame_targets.hpp"

namespace lgh {

struct ShadowRayLayout {
  int shadowedLights = 0;  // the first lights of the lights buffer that get rays
  int lightSamples = 1;    // rays per shadowed light
  int lghSamples = 0;      // k, the LGH's samples per pixel (0: none this frame)
  int raysPerPixel() const { return shadowedLights * lightSamples + lghSamples; }
  int words() const { return (raysPerPixel() + 31) / 32; }
};

struct ShadowRaySetupInputs {
  ShadowRayLayout layout;
  GLuint lights = 0;      // SSBO of GpuLight
  GLuint lghSamples = 0;  // SSBO of vec4 per pixel and sample (layout.lghSamples > 0)
  float surfaceOffset = 0.0F;
  std::uint32_t seed = 1;
};

class ShadowRaySetupPass {
 public:
  // `clearsOrigins` and `unrollsLightLoops` (passes/light_loops.hpp): as the device prefers
  // (tests try both).
  explicit ShadowRaySetupPass(bool clearsOrigins = gl::softwareRasterizer(),
                              bool unrollsLightLoops = gl::softwareRasterizer());
  void run(const ShadowRaySetupInputs& inputs, const FrameTargets& frame, GLuint origins,
           GLuint targets);
  // The shadowed brute-force reference's rays: from every pixel to each of `count` point lights
  // (PointLight SSBO) from `first` on, at their exact positions.
  void runToPointLights(GLuint pointLights, int first, int count, float surfaceOffset,
                        const FrameTargets& frame, GLuint origins, GLuint targets);

 private:
  // Clears the origins first where that is cheaper than the shader's stores (a CPU rasteriser);
  // tells the program whether it did.
  void prepareOrigins(GLuint program, GLuint origins, const FrameTargets& frame) const;
  // Where the origins were cleared, the tiles that can show a surface; else every tile.
  FrameTiles tilesToRun(const FrameTargets& frame) const;

  // The program for `layout`: compiled for its numbers of lights where the loops unroll
  // (passes/light_loops.hpp), built on first use.
  GLuint program(const ShadowRayLayout& layout);

  std::map<std::string, gl::Program> programs_;  // by their defines
  gl::Program pointLightProgram_ = gl::Program::empty();
  bool clearsOrigins_;
  bool unrollsLightLoops_;
};

// Sets the uniforms of glsl/include/ray_batch.glsl on `program`.
void setShadowRayUniforms(GLuint program, const ShadowRayLayout& layout);

}  // namespace lgh
