#include "passes/display_pass.hpp"

#include "passes/composite_pass.hpp"

namespace lgh {

const gl::Program& DisplayPass::program(OutputPixels pixels) {
  const bool display = pixels == OutputPixels::Display8;
  std::optional<gl::Program>& slot = display ? display_ : linear_;
  if (!slot) slot.emplace(buildDisplayProgram("display.frag", "", display));
  return *slot;
}

void DisplayPass::run(const OutputSettings& output, OutputPixels pixels, FrameTargets& targets) {
  glBindFramebuffer(GL_FRAMEBUFFER, targets.output(pixels).framebuffer.id());
  glViewport(0, 0, targets.width, targets.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = this->program(pixels).id();
  glUseProgram(program);
  setDisplayUniforms(program, output, targets.height);
  glBindTextureUnit(0, targets.sceneLinear().texture.id());
  glBindVertexArray(emptyVertexArray_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

}  // namespace lgh
