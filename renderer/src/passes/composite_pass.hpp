// Composite pass.
//   inputs:  FrameTargets::direct, FrameTargets::indirect (when LGH lighting ran) and its shadow
//            ratio (when shadowed), G-buffer coverage, background colour or transparency
//   outputs: FrameTargets::output(pixels), rows turned over: display codes (exposure, tone map,
//            sRGB; RGBA8UI) for a PNG, linear light (RGBA16F / RGBA32F) for an EXR
//   shaders: glsl/fullscreen.vert, glsl/composite.frag (+ include/display_transform.glsl)
// packOutput() then copies the output into a pixel-pack buffer, asynchronously.
#pragma once

#include <optional>

#include "gl/gl_objects.hpp"
#include "lgh/frame_pixels.hpp"
#include "lgh/image.hpp"
#include "lgh/request.hpp"
#include "passes/frame_targets.hpp"

namespace lgh {

class CompositePass {
 public:
  // `shadowRatio`: the filtered LGH shadow ratio texture, 0 for unshadowed LGH lighting.
  void run(const OutputSettings& output, OutputPixels pixels, bool hasIndirect, GLuint shadowRatio,
           FrameTargets& targets);

 private:
  const gl::Program& program(OutputPixels pixels);

  std::optional<gl::Program> display_;  // each compiled on first use
  std::optional<gl::Program> linear_;
  gl::VertexArray emptyVertexArray_;
};

// What a frame of `output` is composited to: display codes for PNG, half or float for EXR.
OutputPixels outputPixelsFor(const OutputSettings& output);

// Issues the copy of the output into `packBuffer` (offset 0) as `layout` (Rgb8 drops the alpha
// codes; the others copy every channel). Returns at once: the bytes are there once a fence
// inserted after it has signalled.
void packOutput(const FrameTargets& targets, OutputPixels pixels, FramePixels::Layout layout,
                GLuint packBuffer);

// Reads a LinearFloat output now (tests and the benchmark's probes).
FloatImage readLinearOutput(FrameTargets& targets);

}  // namespace lgh
