#include "passes/lgh_bruteforce_pass.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "passes/direct_lighting_pass.hpp"

namespace lgh {
namespace {

constexpr int kGroupSize = 8;

GLuint groups(int pixels) { return static_cast<GLuint>((pixels + kGroupSize - 1) / kGroupSize); }

}  // namespace

void LghBruteForcePass::run(GLuint pointLights, int count, GLuint levels,
                            const CameraMatrices& camera, const FrameTargets& frame) {
  if (frame.width != width_ || frame.height != height_) {
    output_ = gl::Texture(GL_TEXTURE_2D);
    glTextureStorage2D(output_.id(), 1, GL_RGBA32F, frame.width, frame.height);
    width_ = frame.width;
    height_ = frame.height;
  }
  const GLuint program = program_.get("", [](const std::string& defines) {
    return gl::buildComputeProgram("lgh_bruteforce.comp", defines);
  });
  glUseProgram(program);
  setUniform(program, "uLightCount", static_cast<GLuint>(count));
  const GLint frameSize = glGetUniformLocation(program, "uFrameSize");
  glProgramUniform2i(program, frameSize, frame.width, frame.height);
  glProgramUniform3fv(program, glGetUniformLocation(program, "uCameraPosition"), 1,
                      glm::value_ptr(camera.position));
  bindGBuffer(frame.gbuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_POINT_LIGHTS, pointLights);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_LEVELS, levels);
  glBindImageTexture(LGH_IMAGE_OUTPUT, output_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(groups(frame.width), groups(frame.height), 1);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  glUseProgram(0);
}

FloatImage LghBruteForcePass::read() const { return readTextureImage(output_, width_, height_); }

}  // namespace lgh
