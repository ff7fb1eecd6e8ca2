// Display pass, for frames with blended surfaces (the others get this from the composite pass).
//   inputs:  FrameTargets::scene: the composite in linear light with the blended surfaces over it
//   outputs: FrameTargets::output(pixels), rows turned over: display codes (exposure, tone map,
//            sRGB; RGBA8UI) for a PNG, linear light (RGBA16F / RGBA32F) for an EXR
//   shaders: glsl/fullscreen.vert, glsl/display.frag (+ include/display_transform.glsl)
// Blending has to happen in linear light, before the display transform: the display codes are
// integers (no blending) and tone mapped.
#pragma once

#include <optional>

#include "gl/gl_objects.hpp"
#include "lgh/request.hpp"
#include "passes/frame_targets.hpp"

namespace lgh {

class DisplayPass {
 public:
  void run(const OutputSettings& output, OutputPixels pixels, FrameTargets& targets);

 private:
  const gl::Program& program(OutputPixels pixels);

  std::optional<gl::Program> display_;  // each compiled on first use
  std::optional<gl::Program> linear_;
  gl::VertexArray emptyVertexArray_;
};

}  // namespace lgh
