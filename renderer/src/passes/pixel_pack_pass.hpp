// Pixel pack pass: the last GPU step of a frame, behind its fence.
//   inputs:  FrameTargets::output(pixels), rows already in the image's order
//   outputs: the frame's pixel-pack buffer (gl/readback_buffers.hpp) holding FramePixels of
//            `layout`: display codes, 3 or 4 bytes per pixel, packed by glsl/pixel_pack.comp (a
//            word per invocation) on a GPU and copied by glGetTextureImage on a CPU rasterizer
//            (and for a frame larger than the driver's shader storage block), or half / float
//            linear light copied by glGetTextureImage (the target's own format)
//   shaders: glsl/pixel_pack.comp
// Two shapes of the same copy, chosen per device by measurement (docs/BENCHMARKS.md): on NVIDIA
// reading an RGBA8UI target as RGB (or as any integer format) into a pack buffer is a slow
// conversion, while on llvmpipe the driver's copy is a loop on the render thread and the shader's
// a dispatch that wakes the compute threads and stores lane by lane.
#pragma once

#include <cstddef>

#include "gl/gl_objects.hpp"
#include "lgh/frame_pixels.hpp"
#include "passes/frame_targets.hpp"

namespace lgh {

// How display codes reach the pack buffer: by the device's choice, or one shape (tests).
enum class PackShape { ForDevice, Shader, DriverCopy };

class PixelPackPass {
 public:
  explicit PixelPackPass(PackShape shape = PackShape::ForDevice);

  // The size of the pack buffer a frame of `pixels` needs (its bytes rounded up to whole words).
  static std::size_t bufferBytes(const FramePixels& pixels);

  // The work groups that cover `invocations` (LGH_PACK_GROUP each: a word each)
  // in rows of at most `maxGroupsX`: GL guarantees only 65,535 groups in a row.
  struct Dispatch {
    unsigned x = 0;
    unsigned y = 0;
  };
  static Dispatch dispatchFor(std::size_t invocations, unsigned maxGroupsX);

  // Issues the copy of the output into `packBuffer` (offset 0) as `layout`; returns at once: the
  // bytes are there once a fence inserted after it has signalled. A dispatch or a copy: no draw
  // (gl::GpuWork::Compute).
  void run(const FrameTargets& targets, OutputPixels pixels, FramePixels::Layout layout,
           GLuint packBuffer);

 private:
  void packDisplayCodes(const FrameTargets& targets, OutputPixels pixels, const FramePixels& frame,
                        GLuint packBuffer);

  bool byShader_;        // display codes packed by glsl/pixel_pack.comp (GPUs)
  gl::Program program_;  // built when byShader_
  unsigned maxGroupsX_ = 65535;
  std::size_t maxBlockBytes_ = std::size_t{1} << 27;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  bool warnedLargeFrame_ = false;
};

}  // namespace lgh
