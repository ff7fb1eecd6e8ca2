#include "passes/composite_pass.hpp"

#include <algorithm>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"

namespace lgh {

CompositePass::CompositePass()
    : program_(gl::buildProgram(
          {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "composite.frag"}})) {}

void CompositePass::run(const OutputSettings& output, bool hasIndirect, GLuint shadowRatio,
                        FrameTargets& targets) {
  glBindFramebuffer(GL_FRAMEBUFFER, targets.finalFramebuffer.id());
  glViewport(0, 0, targets.width, targets.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = program_.id();
  glUseProgram(program);
  glProgramUniform1i(program, glGetUniformLocation(program, "uHasIndirect"), hasIndirect ? 1 : 0);
  glProgramUniform1i(program, glGetUniformLocation(program, "uHasShadowRatio"),
                     shadowRatio != 0 ? 1 : 0);
  glBindTextureUnit(LGH_UNIT_COMPOSITE_RATIO, shadowRatio);
  const float alpha = output.transparentBackground ? 0.0F : 1.0F;
  const auto& bg = output.background;
  glProgramUniform4f(program, glGetUniformLocation(program, "uBackground"), bg[0] * alpha,
                     bg[1] * alpha, bg[2] * alpha, alpha);
  const GLuint textures[3] = {targets.direct.id(), targets.indirect.id(),
                              targets.gbuffer.position.id()};
  glBindTextures(0, 3, textures);
  glBindVertexArray(emptyVertexArray_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

FloatImage readbackFinal(const FrameTargets& targets) {
  FloatImage image;
  image.width = targets.width;
  image.height = targets.height;
  const size_t rowFloats = static_cast<size_t>(targets.width) * 4;
  image.rgba.resize(rowFloats * static_cast<size_t>(targets.height));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(targets.final.id(), 0, GL_RGBA, GL_FLOAT,
                    static_cast<GLsizei>(image.rgba.size() * sizeof(float)), image.rgba.data());
  // GL's rows run bottom-up; images here run top-down. Flipping in place spares a second
  // frame-sized buffer (15 MB at 1280x720) and its page faults.
  for (int top = 0, bottom = targets.height - 1; top < bottom; ++top, --bottom) {
    float* topRow = image.rgba.data() + rowFloats * static_cast<size_t>(top);
    std::swap_ranges(topRow, topRow + rowFloats,
                     image.rgba.data() + rowFloats * static_cast<size_t>(bottom));
  }
  return image;
}

}  // namespace lgh
