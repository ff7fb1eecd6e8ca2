#include "passes/lgh_bruteforce_pass.hpp"

#include <algorithm>

#include <glm/gtc/type_ptr.hpp>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "passes/direct_lighting_pass.hpp"
#include "passes/shadow_ray_setup_pass.hpp"

namespace lgh {
namespace {

constexpr int kRaysPerChunk = 64;  // vk::kMaxRaysPerPixel

}  // namespace

void LghBruteForcePass::run(GLuint pointLights, int count, GLuint levels,
                            const CameraMatrices& camera, const FrameTargets& frame,
                            const BrdfFeatures& brdf, const PointLightVisibility& visibility,
                            float minDistance) {
  if (frame.width != width_ || frame.height != height_) {
    output_ = gl::Texture(GL_TEXTURE_2D);
    glTextureStorage2D(output_.id(), 1, GL_RGBA32F, frame.width, frame.height);
    width_ = frame.width;
    height_ = frame.height;
  }
  const std::string defines =
      (visibility ? "#define LGH_SHADOWED 1\n" : std::string()) + brdf.defines();
  const GLuint program = program_.get(defines, [](const std::string& text) {
    return gl::buildComputeProgram("lgh_bruteforce.comp", text);
  });
  setUniform(program, "uMinDistance2", minDistance < 0.0F ? -1.0F : minDistance * minDistance);
  if (!visibility) {
    setUniform(program, "uLightCount", static_cast<GLuint>(count));
    dispatch(program, pointLights, levels, camera, frame);
    return;
  }
  for (int first = 0; first < std::max(count, 1); first += kRaysPerChunk) {
    const int chunk = std::min(kRaysPerChunk, count - first);
    const GLuint bits = chunk > 0 ? visibility(pointLights, first, chunk) : 0;
    ShadowRayLayout layout;
    layout.lghSamples = std::max(chunk, 1);
    setShadowRayUniforms(program, layout);
    setUniform(program, "uLightCount", static_cast<GLuint>(std::max(chunk, 0)));
    setUniform(program, "uChunkFirst", static_cast<GLuint>(first));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_RAY_VISIBILITY, bits);
    dispatch(program, pointLights, levels, camera, frame);
  }
}

void LghBruteForcePass::dispatch(GLuint program, GLuint pointLights, GLuint levels,
                                 const CameraMatrices& camera, const FrameTargets& frame) {
  glUseProgram(program);
  const GLint frameSize = glGetUniformLocation(program, "uFrameSize");
  glProgramUniform2i(program, frameSize, frame.width, frame.height);
  glProgramUniform3fv(program, glGetUniformLocation(program, "uCameraPosition"), 1,
                      glm::value_ptr(camera.position));
  bindGBuffer(frame.gbuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_POINT_LIGHTS, pointLights);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_LEVELS, levels);
  glBindImageTexture(LGH_IMAGE_OUTPUT, output_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(gl::groups2D(frame.width), gl::groups2D(frame.height), 1);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  glUseProgram(0);
}

FloatImage LghBruteForcePass::read() const { return readTextureImage(output_, width_, height_); }

}  // namespace lgh
