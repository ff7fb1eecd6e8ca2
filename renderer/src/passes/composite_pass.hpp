// Composite pass.
//   inputs:  FrameTargets::direct, FrameTargets::indirect (when LGH lighting ran) and its shadow
//            ratio (when shadowed), G-buffer coverage, background colour or transparency
//   outputs: FrameTargets::output(pixels), rows turned over: display codes (exposure, tone map,
//            sRGB; RGBA8UI) for a PNG, linear light (RGBA16F / RGBA32F) for an EXR;
//            or (runToScene, frames with blended surfaces) FrameTargets::scene, linear light with
//            the rows as GL stores them, for the forward blend and then the display pass
//   shaders: glsl/composite.comp (+ include/display_transform.glsl), a compute pass
// The pixel pack pass (passes/pixel_pack_pass.hpp) then copies the output into a read-back buffer.
// A frame with nothing to composite (direct lighting alone, no blended surfaces) skips this pass:
// DirectLightingPass::runToOutput writes its output, through the same
// glsl/include/frame_output.glsl.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "gl/gl_objects.hpp"
#include "gl/software_rasterizer.hpp"
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
  // The same sum into FrameTargets::sceneLinear(): blending happens in linear light, before the
  // display transform (passes/display_pass.hpp).
  void runToScene(const OutputSettings& output, bool hasIndirect, GLuint shadowRatio,
                  FrameTargets& targets);

 private:
  void dispatch(const OutputSettings& output, OutputPixels pixels, bool toScene, bool hasIndirect,
                GLuint shadowRatio, FrameTargets& targets);
  const gl::Program& program(OutputPixels pixels, bool toScene);

  std::array<std::optional<gl::Program>, 3> programs_;  // by OutputPixels, compiled on first use
  std::optional<gl::Program> scene_;
  bool clearsBackground_ = gl::softwareRasterizer();  // bindFrameOutput's clearFirst
};

// Uploads the sRGB thresholds of include/display_transform.glsl to a program that includes it.
void uploadSrgbThresholds(GLuint program);
// A fullscreen program of glsl/fullscreen.vert + `fragmentShader` with `defines`; `display` adds
// LGH_DISPLAY_OUTPUT and uploads the sRGB thresholds.
gl::Program buildDisplayProgram(const char* fragmentShader, const std::string& defines,
                                bool display);
// uHeight, uToneMap and uExposure of a program that writes output(pixels) (unused ones ignored).
void setDisplayUniforms(GLuint program, const OutputSettings& output, int height);

// What a frame of `output` is composited to: display codes for PNG, half or float for EXR.
OutputPixels outputPixelsFor(const OutputSettings& output);

// A compute program of `computeShader` + `defines` that writes output(pixels) through
// include/frame_output.glsl: the output's defines added and, for display codes, the sRGB
// thresholds uploaded.
gl::Program buildFrameOutputProgram(const char* computeShader, const std::string& defines,
                                    OutputPixels pixels);
// Binds output(pixels) to such a program's image unit and sets its uniforms: the frame's height,
// the background, and for display codes the tone map and exposure. `clearFirst` (a CPU
// rasteriser): the output is cleared to the background first, and the program's groups of
// background pixels store nothing (include/frame_output.glsl).
void bindFrameOutput(GLuint program, const OutputSettings& output, OutputPixels pixels,
                     FrameTargets& targets, bool clearFirst);

// Reads a LinearFloat output now (tests and the benchmark's probes).
FloatImage readLinearOutput(FrameTargets& targets);

}  // namespace lgh
