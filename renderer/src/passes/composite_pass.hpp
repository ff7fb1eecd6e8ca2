// Composite pass.
//   inputs:  FrameTargets::direct, FrameTargets::indirect (when LGH lighting ran) and its shadow
//            ratio (when shadowed), G-buffer coverage, background colour or transparency
//   outputs: FrameTargets::final (linear RGBA32F), read back by readbackFinal()
//   shaders: glsl/fullscreen.vert, glsl/composite.frag
#pragma once

#include "gl/gl_objects.hpp"
#include "lgh/image.hpp"
#include "lgh/request.hpp"
#include "passes/frame_targets.hpp"

namespace lgh {

class CompositePass {
 public:
  CompositePass();
  // `shadowRatio`: the filtered LGH shadow ratio texture, 0 for unshadowed LGH lighting.
  void run(const OutputSettings& output, bool hasIndirect, GLuint shadowRatio,
           FrameTargets& targets);

 private:
  gl::Program program_;
  gl::VertexArray emptyVertexArray_;
};

// Reads FrameTargets::final into a top-to-bottom FloatImage.
FloatImage readbackFinal(const FrameTargets& targets);

}  // namespace lgh
