// Pixel pack pass: the last GPU step of a frame, behind its fence.
//   inputs:  FrameTargets::output(pixels), rows already in the image's order
//   outputs: the frame's pixel-pack buffer (gl/readback_buffers.hpp) holding FramePixels of
//            `layout`: display codes packed 3 or 4 bytes per pixel by glsl/pixel_pack.comp, a
//            word per invocation on a GPU and four pixels per invocation on a CPU rasterizer (by
//            glGetTextureImage for a frame larger than the driver's shader storage block), or
//            half / float linear light copied by glGetTextureImage (the target's own format)
//   shaders: glsl/pixel_pack.comp
// Display codes are packed by a compute shader rather than by glGetTextureImage: reading an
// RGBA8UI target as RGB (or as any integer format) into a pack buffer is a slow conversion in
// some drivers (docs/BENCHMARKS.md, "Output").
#pragma once

#include <cstddef>

#include "gl/gl_objects.hpp"
#include "gl/gpu_timer.hpp"
#include "lgh/frame_pixels.hpp"
#include "passes/frame_targets.hpp"

namespace lgh {

class PixelPackPass {
 public:
  PixelPackPass();

  // The size of the pack buffer a frame of `pixels` needs (its bytes rounded up to whole words).
  static std::size_t bufferBytes(const FramePixels& pixels);

  // The work groups that cover `invocations` (LGH_PACK_GROUP each: a word, or four pixels, each)
  // in rows of at most `maxGroupsX`: GL guarantees only 65,535 groups in a row.
  struct Dispatch {
    unsigned x = 0;
    unsigned y = 0;
  };
  static Dispatch dispatchFor(std::size_t invocations, unsigned maxGroupsX);

  // Issues the copy of the output into `packBuffer` (offset 0) as `layout`; returns at once: the
  // bytes are there once a fence inserted after it has signalled.
  void run(const FrameTargets& targets, OutputPixels pixels, FramePixels::Layout layout,
           GLuint packBuffer);
  // What run() issues for such a frame: a compute dispatch, or a copy by the driver (which may
  // draw).
  gl::GpuWork work(const FrameTargets& targets, FramePixels::Layout layout) const;

 private:
  bool packsByShader(const FramePixels& frame) const {
    return frame.isDisplay() && bufferBytes(frame) <= maxBlockBytes_;
  }
  void packDisplayCodes(const FrameTargets& targets, OutputPixels pixels, const FramePixels& frame,
                        GLuint packBuffer);

  bool fourPixelsPerInvocation_;  // LGH_PACK_FOUR_PIXELS: on a CPU rasterizer
  gl::Program program_;
  unsigned maxGroupsX_ = 65535;
  std::size_t maxBlockBytes_ = std::size_t{1} << 27;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  bool warnedLargeFrame_ = false;
};

}  // namespace lgh
