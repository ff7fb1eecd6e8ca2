#include "passes/pixel_pack_pass.hpp"

#include <algorithm>

#include <spdlog/spdlog.h>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "gl/software_rasterizer.hpp"

namespace lgh {
namespace {

constexpr std::size_t kWordBytes = 4;

std::size_t wordsFor(std::size_t bytes) { return (bytes + kWordBytes - 1) / kWordBytes; }

// glGetTextureImage into the pack buffer, in the layout's format.
void copyByDriver(const FrameTargets& targets, OutputPixels pixels, const FramePixels& frame,
                  GLuint packBuffer) {
  GLenum format = GL_RGBA;
  GLenum type = GL_FLOAT;
  switch (frame.layout) {
    case FramePixels::Layout::Rgb8:
      format = GL_RGB_INTEGER;
      type = GL_UNSIGNED_BYTE;
      break;
    case FramePixels::Layout::Rgba8:
      format = GL_RGBA_INTEGER;
      type = GL_UNSIGNED_BYTE;
      break;
    case FramePixels::Layout::RgbaHalf:
      type = GL_HALF_FLOAT;
      break;
    case FramePixels::Layout::RgbaFloat:
      break;
  }
  glPixelStorei(GL_PACK_ALIGNMENT, 1);  // rows tightly packed, whatever their length
  glBindBuffer(GL_PIXEL_PACK_BUFFER, packBuffer);
  glGetTextureImage(targets.outputs[static_cast<int>(pixels)].texture.id(), 0, format, type,
                    static_cast<GLsizei>(frame.size()), nullptr);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
}

bool packsByShader(PackShape shape) {
  switch (shape) {
    case PackShape::Shader:
      return true;
    case PackShape::DriverCopy:
      return false;
    case PackShape::ForDevice:
      break;
  }
  return !gl::softwareRasterizer();
}

}  // namespace

PixelPackPass::PixelPackPass(PackShape shape)
    : byShader_(packsByShader(shape)),
      program_(byShader_ ? gl::buildComputeProgram("pixel_pack.comp") : gl::Program::empty()) {
  GLint maxGroupsX = 65535;
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &maxGroupsX);
  maxGroupsX_ = static_cast<unsigned>(std::max(maxGroupsX, 1));
  GLint64 maxBlockBytes = 1 << 27;  // GL's guaranteed minimum
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlockBytes);
  maxBlockBytes_ = static_cast<std::size_t>(std::max<GLint64>(maxBlockBytes, 0));
}

PixelPackPass::Dispatch PixelPackPass::dispatchFor(std::size_t invocations, unsigned maxGroupsX) {
  const std::size_t groups = (invocations + LGH_PACK_GROUP - 1) / LGH_PACK_GROUP;
  if (groups == 0) return {};
  const std::size_t x = std::min<std::size_t>(groups, std::max(maxGroupsX, 1U));
  return {static_cast<unsigned>(x), static_cast<unsigned>((groups + x - 1) / x)};
}

std::size_t PixelPackPass::bufferBytes(const FramePixels& pixels) {
  return wordsFor(pixels.size()) * kWordBytes;
}

void PixelPackPass::run(const FrameTargets& targets, OutputPixels pixels,
                        FramePixels::Layout layout, GLuint packBuffer) {
  const FramePixels frame{targets.width, targets.height, layout, nullptr};
  if (!frame.isDisplay() || !byShader_) {
    // The target's own format, or display codes where the driver's copy is the faster shape.
    copyByDriver(targets, pixels, frame, packBuffer);
    return;
  }
  if (bufferBytes(frame) > maxBlockBytes_) {
    if (!warnedLargeFrame_) {
      spdlog::info(
          "renderer: frames over {} MB are read back by glGetTextureImage (the "
          "driver's storage-block limit), which is slower on some drivers",
          maxBlockBytes_ >> 20);
      warnedLargeFrame_ = true;
    }
    copyByDriver(targets, pixels, frame, packBuffer);
    return;
  }
  packDisplayCodes(targets, pixels, frame, packBuffer);
}

void PixelPackPass::packDisplayCodes(const FrameTargets& targets, OutputPixels pixels,
                                     const FramePixels& frame, GLuint packBuffer) {
  const std::size_t words = wordsFor(frame.size());
  const std::size_t pixelCount = static_cast<std::size_t>(frame.width) * frame.height;
  const GLuint program = program_.id();
  glUseProgram(program);
  glProgramUniform1i(program, glGetUniformLocation(program, "uWidth"), targets.width);
  glProgramUniform1i(program, glGetUniformLocation(program, "uChannels"), frame.channels());
  glProgramUniform1ui(program, glGetUniformLocation(program, "uWordCount"),
                      static_cast<GLuint>(words));
  glProgramUniform1ui(program, glGetUniformLocation(program, "uPixelCount"),
                      static_cast<GLuint>(pixelCount));
  glBindTextureUnit(0, targets.outputs[static_cast<int>(pixels)].texture.id());
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, LGH_BIND_PACKED_PIXELS, packBuffer, 0,
                    static_cast<GLsizeiptr>(words * kWordBytes));
  const Dispatch groups = dispatchFor(words, maxGroupsX_);
  glDispatchCompute(groups.x, groups.y, 1);
  // The buffer is mapped persistently: the CPU reads it once the frame's fence has signalled.
  glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_PACKED_PIXELS, 0);
  glBindTextureUnit(0, 0);
}

}  // namespace lgh
