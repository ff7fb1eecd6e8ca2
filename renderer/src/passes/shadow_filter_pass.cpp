#include "passes/shadow_filter_pass.hpp"

#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "passes/direct_lighting_pass.hpp"

namespace lgh {
namespace {

GLint location(GLuint program, const char* name) { return glGetUniformLocation(program, name); }

// Normals must agree closely (cos^64: 0.5 at 8.4 degrees); taps more than a few footprints off
// the pixel's tangent plane hardly count. Both fixed: the paper gives no values.
constexpr float kPlaneSigma = 1.0F;

// World size of a pixel at distance d: d * x + y.
glm::vec2 pixelFootprint(const CameraMatrices& camera, int height) {
  const float scale = 2.0F / (camera.projection[1][1] * static_cast<float>(height));
  const bool orthographic = camera.projection[3][3] == 1.0F;
  return orthographic ? glm::vec2(0.0F, scale) : glm::vec2(scale, 0.0F);
}

gl::Texture ratioTexture(int width, int height) {
  gl::Texture texture(GL_TEXTURE_2D);
  glTextureStorage2D(texture.id(), 1, GL_R16F, width, height);
  glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return texture;
}

}  // namespace

ShadowFilterPass::ShadowFilterPass()
    : ratioProgram_(gl::buildComputeProgram("shadow_ratio.comp")),
      atrousProgram_(gl::buildComputeProgram("shadow_atrous.comp")) {}

void ShadowFilterPass::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  ping_ = ratioTexture(width, height);
  pong_ = ratioTexture(width, height);
  width_ = width;
  height_ = height;
}

GLuint ShadowFilterPass::run(const ShadowFilterInputs& inputs, const CameraMatrices& camera,
                             const FrameTargets& frame) {
  resize(frame.width, frame.height);
  GLuint current = ping_.id();
  GLuint other = pong_.id();
  ratio(inputs, frame, current);
  for (int i = 0; i < inputs.iterations; ++i) {
    atrous(1 << i, camera, frame, current, other);
    std::swap(current, other);
  }
  return current;
}

void ShadowFilterPass::ratio(const ShadowFilterInputs& inputs, const FrameTargets& frame,
                             GLuint output) {
  const GLuint program = ratioProgram_.id();
  glUseProgram(program);
  setShadowRayUniforms(program, inputs.layout);
  glProgramUniform2i(program, location(program, "uFrameSize"), frame.width, frame.height);
  glProgramUniform1i(program, location(program, "uLghSampleCount"), inputs.layout.lghSamples);
  glProgramUniform1i(program, location(program, "uFirstLghRay"),
                     inputs.layout.shadowedLights * inputs.layout.lightSamples);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_RAY_VISIBILITY, inputs.visibility);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_SAMPLES, inputs.lghSamples);
  glBindImageTexture(LGH_IMAGE_SHADOW_RATIO, output, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
  glDispatchCompute(gl::groups2D(frame.width), gl::groups2D(frame.height), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void ShadowFilterPass::atrous(int step, const CameraMatrices& camera, const FrameTargets& frame,
                              GLuint input, GLuint output) {
  const GLuint program = atrousProgram_.id();
  glUseProgram(program);
  glProgramUniform2i(program, location(program, "uFrameSize"), frame.width, frame.height);
  glProgramUniform1i(program, location(program, "uStep"), step);
  glProgramUniform3fv(program, location(program, "uCameraPosition"), 1,
                      glm::value_ptr(camera.position));
  const glm::vec2 footprint = pixelFootprint(camera, frame.height);
  glProgramUniform2f(program, location(program, "uFootprint"), footprint.x, footprint.y);
  glProgramUniform1f(program, location(program, "uPlaneSigma"), kPlaneSigma);
  bindGBuffer(frame.gbuffer);
  glBindTextureUnit(LGH_UNIT_PASS_INPUT, input);
  glBindImageTexture(LGH_IMAGE_SHADOW_RATIO, output, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
  glDispatchCompute(gl::groups2D(frame.width), gl::groups2D(frame.height), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace lgh
