#include "passes/lgh_interleave_pass.hpp"

#include <algorithm>
#include <array>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "passes/direct_lighting_pass.hpp"

namespace lgh {
namespace {

constexpr int kGroupSize = 8;

GLuint groups(int pixels) { return static_cast<GLuint>((pixels + kGroupSize - 1) / kGroupSize); }

// World size of a pixel at unit distance: 2 tan(fovy / 2) / H from the projection matrix.
float pixelFootprint(const CameraMatrices& camera, int height) {
  const float cotHalfFov = camera.projection[1][1];
  return cotHalfFov > 0.0F ? 2.0F / (cotHalfFov * static_cast<float>(std::max(height, 1))) : 1e-3F;
}

}  // namespace

void LghInterleavePass::split(const LghLightingParams& params, const CameraMatrices& camera,
                              FrameTargets& frame, LghLightingTargets& targets) {
  const GLuint program = splitProgram_.get("", [](const std::string& defines) {
    return gl::buildProgram(
        {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "lgh_interleave_split.frag"}},
        defines);
  });
  glBindFramebuffer(GL_FRAMEBUFFER, targets.tiles.framebuffer.id());
  glViewport(0, 0, targets.atlasWidth(), targets.atlasHeight());
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  glDepthMask(GL_TRUE);
  glEnable(GL_FRAMEBUFFER_SRGB);  // the tile albedo is sRGB like the G-buffer's: exact copy
  glUseProgram(program);
  setLightingUniforms(program, params, targets, camera);
  bindGBuffer(frame.gbuffer);
  glBindTextureUnit(LGH_UNIT_PASS_INPUT, frame.gbuffer.depth.id());
  glBindVertexArray(emptyVertexArray_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDepthFunc(GL_LESS);
  glDisable(GL_DEPTH_TEST);
  glUseProgram(0);
}

void LghInterleavePass::composite(const LghLightingParams& params, const CameraMatrices& camera,
                                  FrameTargets& frame, LghLightingTargets& targets) {
  const GLuint program = compositeProgram_.get("", [](const std::string& defines) {
    return gl::buildComputeProgram("lgh_interleave_composite.comp", defines);
  });
  glUseProgram(program);
  setLightingUniforms(program, params, targets, camera);
  setUniform(program, "uPixelFootprint", pixelFootprint(camera, targets.height));
  bindGBuffer(frame.gbuffer);
  glBindTextureUnit(LGH_UNIT_PASS_INPUT, targets.accumulation.id());
  glBindImageTexture(LGH_IMAGE_OUTPUT, frame.indirect.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                     GL_RGBA16F);
  glDispatchCompute(groups(targets.width), groups(targets.height), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
  glUseProgram(0);
}

}  // namespace lgh
