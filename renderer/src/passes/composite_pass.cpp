#include "passes/composite_pass.hpp"

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "image/image_common.hpp"

namespace lgh {
namespace {

int toneMapCode(ToneMap toneMap) {
  switch (toneMap) {
    case ToneMap::None:
      return 0;  // LGH_TONE_MAP_NONE
    case ToneMap::Reinhard:
      return 1;  // LGH_TONE_MAP_REINHARD
    case ToneMap::Aces:
      return 2;  // LGH_TONE_MAP_ACES
  }
  return 0;
}

}  // namespace

void setDisplayUniforms(GLuint program, const OutputSettings& output, int height) {
  glProgramUniform1i(program, glGetUniformLocation(program, "uHeight"), height);
  glProgramUniform1i(program, glGetUniformLocation(program, "uToneMap"),
                     toneMapCode(output.toneMap));
  glProgramUniform1f(program, glGetUniformLocation(program, "uExposure"), output.exposure);
}

gl::Program buildDisplayProgram(const char* fragmentShader, const std::string& defines,
                                bool display) {
  gl::Program program = gl::buildProgram(
      {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, fragmentShader}},
      defines + (display ? "#define LGH_DISPLAY_OUTPUT 1\n" : ""));
  if (display) {
    const auto& thresholds = image_io::detail::srgbThresholds();
    glProgramUniform1fv(program.id(), glGetUniformLocation(program.id(), "uSrgbThresholds"), 255,
                        thresholds.data());
  }
  return program;
}

OutputPixels outputPixelsFor(const OutputSettings& output) {
  switch (output.format) {
    case ImageFormat::Png:
      return OutputPixels::Display8;
    case ImageFormat::ExrHalf:
      return OutputPixels::LinearHalf;
    case ImageFormat::ExrFloat:
      return OutputPixels::LinearFloat;
  }
  return OutputPixels::Display8;
}

const gl::Program& CompositePass::program(OutputPixels pixels, bool toScene) {
  if (toScene) {
    if (!scene_) {
      scene_.emplace(buildDisplayProgram("composite.frag", "#define LGH_SCENE_TARGET 1\n", false));
    }
    return *scene_;
  }
  const bool display = pixels == OutputPixels::Display8;
  std::optional<gl::Program>& slot = display ? display_ : linear_;
  if (!slot) slot.emplace(buildDisplayProgram("composite.frag", "", display));
  return *slot;
}

void CompositePass::run(const OutputSettings& output, OutputPixels pixels, bool hasIndirect,
                        GLuint shadowRatio, FrameTargets& targets) {
  draw(output, pixels, false, hasIndirect, shadowRatio, targets);
}

void CompositePass::runToScene(const OutputSettings& output, bool hasIndirect, GLuint shadowRatio,
                               FrameTargets& targets) {
  draw(output, OutputPixels::LinearFloat, true, hasIndirect, shadowRatio, targets);
}

void CompositePass::draw(const OutputSettings& output, OutputPixels pixels, bool toScene,
                         bool hasIndirect, GLuint shadowRatio, FrameTargets& targets) {
  const OutputTarget& target = toScene ? targets.sceneLinear() : targets.output(pixels);
  glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
  glViewport(0, 0, targets.width, targets.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = this->program(pixels, toScene).id();
  glUseProgram(program);
  glProgramUniform1i(program, glGetUniformLocation(program, "uHasIndirect"), hasIndirect ? 1 : 0);
  glProgramUniform1i(program, glGetUniformLocation(program, "uHasShadowRatio"),
                     shadowRatio != 0 ? 1 : 0);
  setDisplayUniforms(program, output, targets.height);
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

FloatImage readLinearOutput(FrameTargets& targets) {
  FloatImage image;
  image.width = targets.width;
  image.height = targets.height;
  image.rgba.resize(static_cast<std::size_t>(targets.width) * targets.height * 4);
  glGetTextureImage(targets.output(OutputPixels::LinearFloat).texture.id(), 0, GL_RGBA, GL_FLOAT,
                    static_cast<GLsizei>(image.rgba.size() * sizeof(float)), image.rgba.data());
  return image;
}

}  // namespace lgh
