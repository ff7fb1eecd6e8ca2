#include "passes/composite_pass.hpp"

#include <array>

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

void uploadSrgbThresholds(GLuint program) {
  const auto& thresholds = image_io::detail::srgbThresholds();
  glProgramUniform1fv(program, glGetUniformLocation(program, "uSrgbThresholds"), 255,
                      thresholds.data());
}

gl::Program buildDisplayProgram(const char* fragmentShader, const std::string& defines,
                                bool display) {
  gl::Program program = gl::buildProgram(
      {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, fragmentShader}},
      defines + (display ? "#define LGH_DISPLAY_OUTPUT 1\n" : ""));
  if (display) uploadSrgbThresholds(program.id());
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

namespace {

// The composite's image format for a target: what glsl/composite.comp stores through.
GLenum imageFormat(OutputPixels pixels) {
  switch (pixels) {
    case OutputPixels::Display8:
      return GL_RGBA8UI;
    case OutputPixels::LinearHalf:
      return GL_RGBA16F;
    case OutputPixels::LinearFloat:
      return GL_RGBA32F;
  }
  return GL_RGBA32F;
}

gl::Program buildCompositeProgram(OutputPixels pixels, bool toScene) {
  if (toScene) return gl::buildComputeProgram("composite.comp", "#define LGH_SCENE_TARGET 1\n");
  return buildFrameOutputProgram("composite.comp", "", pixels);
}

// The background as the output holds it: linear (alpha 0 when transparent, the colour scaled by
// it) and, for display codes, that pixel through the CPU's display transform, which the GPU's
// follows step for step.
struct Background {
  FloatImage linear;
  std::array<GLuint, 4> codes{};
};

Background backgroundOf(const OutputSettings& output) {
  const float alpha = output.transparentBackground ? 0.0F : 1.0F;
  const auto& bg = output.background;
  Background background{{1, 1, {bg[0] * alpha, bg[1] * alpha, bg[2] * alpha, alpha}}, {}};
  const Image8 codes = toDisplay8(background.linear, output.toneMap, output.exposure, true);
  for (std::size_t i = 0; i < background.codes.size(); ++i) background.codes[i] = codes.pixels[i];
  return background;
}

void setBackground(GLuint program, const Background& background) {
  glProgramUniform4fv(program, glGetUniformLocation(program, "uBackground"), 1,
                      background.linear.rgba.data());
  glProgramUniform4uiv(program, glGetUniformLocation(program, "uBackgroundCodes"), 1,
                       background.codes.data());
}

// The whole output to the background, so that the pass stores no group of background pixels
// (include/frame_output.glsl).
void clearToBackground(GLuint texture, OutputPixels pixels, const Background& background) {
  if (pixels == OutputPixels::Display8) {
    glClearTexImage(texture, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, background.codes.data());
  } else {
    glClearTexImage(texture, 0, GL_RGBA, GL_FLOAT, background.linear.rgba.data());
  }
}

std::string frameOutputDefines(OutputPixels pixels) {
  switch (pixels) {
    case OutputPixels::Display8:
      return "#define LGH_DISPLAY_OUTPUT 1\n";
    case OutputPixels::LinearHalf:
      return "#define LGH_OUTPUT_FORMAT rgba16f\n";
    case OutputPixels::LinearFloat:
      return "#define LGH_OUTPUT_FORMAT rgba32f\n";
  }
  return "#define LGH_OUTPUT_FORMAT rgba32f\n";
}

}  // namespace

gl::Program buildFrameOutputProgram(const char* computeShader, const std::string& defines,
                                    OutputPixels pixels) {
  gl::Program program =
      gl::buildComputeProgram(computeShader, defines + frameOutputDefines(pixels));
  if (pixels == OutputPixels::Display8) uploadSrgbThresholds(program.id());
  return program;
}

void bindFrameOutput(GLuint program, const OutputSettings& output, OutputPixels pixels,
                     FrameTargets& targets, bool clearFirst) {
  setDisplayUniforms(program, output, targets.height);
  const Background background = backgroundOf(output);
  setBackground(program, background);
  const GLuint texture = targets.output(pixels).texture.id();
  if (clearFirst) clearToBackground(texture, pixels, background);
  glProgramUniform1i(program, glGetUniformLocation(program, "uBackgroundCleared"),
                     clearFirst ? 1 : 0);
  glBindImageTexture(LGH_IMAGE_OUTPUT, texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, imageFormat(pixels));
}

const gl::Program& CompositePass::program(OutputPixels pixels, bool toScene) {
  // The scene target is linear float; the outputs one program per kind of pixels.
  std::optional<gl::Program>& slot = toScene ? scene_ : programs_[static_cast<std::size_t>(pixels)];
  if (!slot) {
    slot.emplace(buildCompositeProgram(toScene ? OutputPixels::LinearFloat : pixels, toScene));
  }
  return *slot;
}

void CompositePass::run(const OutputSettings& output, OutputPixels pixels, bool hasIndirect,
                        GLuint shadowRatio, FrameTargets& targets) {
  dispatch(output, pixels, false, hasIndirect, shadowRatio, targets);
}

void CompositePass::runToScene(const OutputSettings& output, bool hasIndirect, GLuint shadowRatio,
                               FrameTargets& targets) {
  dispatch(output, OutputPixels::LinearFloat, true, hasIndirect, shadowRatio, targets);
}

void CompositePass::dispatch(const OutputSettings& output, OutputPixels pixels, bool toScene,
                             bool hasIndirect, GLuint shadowRatio, FrameTargets& targets) {
  const GLuint program = this->program(pixels, toScene).id();
  glUseProgram(program);
  glProgramUniform1i(program, glGetUniformLocation(program, "uHasIndirect"), hasIndirect ? 1 : 0);
  glProgramUniform1i(program, glGetUniformLocation(program, "uHasShadowRatio"),
                     shadowRatio != 0 ? 1 : 0);
  glProgramUniform1i(program, glGetUniformLocation(program, "uWidth"), targets.width);
  glBindTextureUnit(LGH_UNIT_COMPOSITE_RATIO, shadowRatio);
  const GLuint textures[3] = {targets.direct.id(), targets.indirect.id(),
                              targets.gbuffer.position.id()};
  glBindTextures(0, 3, textures);
  if (toScene) {
    glProgramUniform1i(program, glGetUniformLocation(program, "uHeight"), targets.height);
    setBackground(program, backgroundOf(output));
    glBindImageTexture(LGH_IMAGE_OUTPUT, targets.sceneLinear().texture.id(), 0, GL_FALSE, 0,
                       GL_WRITE_ONLY, GL_RGBA32F);
  } else {
    bindFrameOutput(program, output, pixels, targets, clearsBackground_);
  }
  glDispatchCompute(gl::groups2D(targets.width), gl::groups2D(targets.height), 1);
  // Read next by the pixel pack pass, a read-back, or the forward blend's framebuffer.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                  GL_PIXEL_BUFFER_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
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
