#include "passes/lgh_raster_lighting_pass.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "lightgrid/lgh_types.hpp"
#include "passes/direct_lighting_pass.hpp"

namespace lgh {
namespace {

constexpr GLuint kCubeVertices = 36;
constexpr int kGroupSize = 8;

GLuint groups(int pixels) { return static_cast<GLuint>((pixels + kGroupSize - 1) / kGroupSize); }

void bindReservoirStorage(const LghLightingTargets& targets) {
  glBindImageTexture(LGH_IMAGE_RESERVOIR_SUM, targets.reservoirSum.id(), 0, GL_FALSE, 0,
                     GL_READ_WRITE, GL_R32F);
  glBindImageTexture(LGH_IMAGE_LOCK, targets.lock.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  glBindImageTexture(LGH_IMAGE_OVERDRAW, targets.overdraw.id(), 0, GL_FALSE, 0, GL_READ_WRITE,
                     GL_R32UI);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_SAMPLES, targets.shadowSamples.id());
}

// Additive accumulation of back faces that lie behind the surface; no depth writes, and depth
// clamping so that volumes reaching past the far plane still cover their pixels.
void setVolumeState() {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_DEPTH_CLAMP);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  glEnable(GL_SCISSOR_TEST);
}

void restoreState() {
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_CLAMP);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glDisable(GL_DEPTH_TEST);
}

}  // namespace

LghRasterLightingPass::LghRasterLightingPass()
    : interlockAvailable_(gl::api("extension flags").ARB_fragment_shader_interlock != 0) {
  tileDraws_.reserve(16 * sizeof(DrawArraysIndirectCommand));
}

LghRasterLightingPass::LockMode LghRasterLightingPass::lockMode(bool locked) const {
  if (!locked) return LockMode::None;
  return interlockAvailable_ ? LockMode::Interlock : LockMode::SpinLock;
}

glm::vec4 LghRasterLightingPass::tileTransform(int tileX, int tileY,
                                               const LghLightingTargets& targets) {
  // Full-frame pixel centre X = i n + t + 0.5 must land on tile pixel centre u = i + 0.5:
  // u = (X - t - 0.5) / n + 0.5, with X = (x + 1) W / 2 and x' = 2 u / w_tile - 1.
  auto axis = [&](int tile, int frame, int tileSize) {
    const auto n = static_cast<float>(targets.interleave);
    const auto size = static_cast<float>(tileSize);
    const auto full = static_cast<float>(frame);
    const float scale = full / (n * size);
    const float offset = (full - 2.0F * static_cast<float>(tile) - 1.0F + n) / (n * size) - 1.0F;
    return glm::vec2(scale, offset);
  };
  const glm::vec2 x = axis(tileX, targets.width, targets.tileWidth);
  const glm::vec2 y = axis(tileY, targets.height, targets.tileHeight);
  return {x[0], y[0], x[1], y[1]};
}

std::string LghRasterLightingPass::fragmentDefines(const LghLightingParams& params) const {
  std::string defines;
  switch (lockMode(params.locked)) {
    case LockMode::None:
      defines += "#define LGH_LOCK_MODE 0\n";
      break;
    case LockMode::Interlock:
      defines += "#define LGH_LOCK_MODE 1\n";
      break;
    case LockMode::SpinLock:
      defines += "#define LGH_LOCK_MODE 2\n";
      break;
  }
  if (params.overdraw) defines += "#define LGH_OVERDRAW 1\n";
  return defines + params.brdf.defines();
}

void LghRasterLightingPass::run(const LghHierarchyBuffers& hierarchy,
                                const LghLightingParams& params, const CameraMatrices& camera,
                                FrameTargets& frame, LghLightingTargets& targets) {
  targets.clearReservoir();
  if (params.overdraw) targets.clearOverdraw();
  bindHierarchy(hierarchy);
  writeDrawCommands(params, targets);
  const GLuint depth = targets.interleave > 1 ? targets.tiles.depth.id() : frame.gbuffer.depth.id();
  glBindFramebuffer(GL_FRAMEBUFFER, targets.accumulationFramebuffer(depth));
  const float zero[4] = {0.0F, 0.0F, 0.0F, 0.0F};
  glClearBufferfv(GL_COLOR, 0, zero);
  bindGBuffer(targets.interleave > 1 ? targets.tiles : frame.gbuffer);
  bindReservoirStorage(targets);
  glBindVertexArray(emptyVertexArray_.id());
  setVolumeState();
  drawLightVolumes(params, camera, targets);
  drawTopLevel(params, camera, targets);
  restoreState();
  glBindVertexArray(0);
  resolve(params, camera, frame, targets);
}

void LghRasterLightingPass::writeDrawCommands(const LghLightingParams& params,
                                              const LghLightingTargets& targets) {
  const GLuint program = commandPrograms_.get("", [](const std::string& defines) {
    return gl::buildComputeProgram("lgh_interleave_commands.comp", defines);
  });
  glUseProgram(program);
  setUniform(program, "uStartLevel", params.startLevel);
  setUniform(program, "uInterleave", targets.interleave);
  setUniform(program, "uVertexCount", kCubeVertices);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_TILE_DRAWS, tileDraws_.id());
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT);
}

void LghRasterLightingPass::drawLightVolumes(const LghLightingParams& params,
                                             const CameraMatrices& camera,
                                             LghLightingTargets& targets) {
  const GLuint program =
      volumePrograms_.get(fragmentDefines(params), [](const std::string& defines) {
        return gl::buildProgram({{GL_VERTEX_SHADER, "lgh_light_volume.vert"},
                                 {GL_FRAGMENT_SHADER, "lgh_light_volume.frag"}},
                                defines);
      });
  glUseProgram(program);
  setLightingUniforms(program, params, targets, camera);
  const glm::mat4 viewProjection = camera.viewProjection();
  glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "uViewProjection"), 1, GL_FALSE,
                            glm::value_ptr(viewProjection));
  const GLint tileLocation = glGetUniformLocation(program, "uTile");
  const GLint transformLocation = glGetUniformLocation(program, "uTileTransform");
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, tileDraws_.id());
  const int n = targets.interleave;
  for (int ty = 0; ty < n; ++ty) {
    for (int tx = 0; tx < n; ++tx) {
      const int tile = tx + n * ty;
      glViewport(tx * targets.tileWidth, ty * targets.tileHeight, targets.tileWidth,
                 targets.tileHeight);
      glScissor(tx * targets.tileWidth, ty * targets.tileHeight, targets.tileWidth,
                targets.tileHeight);
      glProgramUniform1i(program, tileLocation, tile);
      glProgramUniform4fv(program, transformLocation, 1,
                          glm::value_ptr(tileTransform(tx, ty, targets)));
      // GL takes the offset into the bound indirect buffer as a pointer.
      const std::uintptr_t offset =
          static_cast<std::uintptr_t>(tile) * sizeof(DrawArraysIndirectCommand);
      // NOLINTNEXTLINE(performance-no-int-to-ptr)
      glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(offset));
    }
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

void LghRasterLightingPass::drawTopLevel(const LghLightingParams& params,
                                         const CameraMatrices& camera,
                                         LghLightingTargets& targets) {
  // The top level streams into the same reservoirs after every light volume.
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  const GLuint program = topPrograms_.get(fragmentDefines(params), [](const std::string& defines) {
    return gl::buildProgram(
        {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "lgh_top_level.frag"}},
        defines);
  });
  glUseProgram(program);
  setLightingUniforms(program, params, targets, camera);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glViewport(0, 0, targets.atlasWidth(), targets.atlasHeight());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void LghRasterLightingPass::resolve(const LghLightingParams& params, const CameraMatrices& camera,
                                    FrameTargets& frame, LghLightingTargets& targets) {
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                  GL_TEXTURE_FETCH_BARRIER_BIT);
  const bool copy = targets.interleave == 1;
  const GLuint program = resolvePrograms_.get(
      copy ? "#define LGH_RESOLVE_COPY 1\n" : "", [](const std::string& defines) {
        return gl::buildComputeProgram("lgh_resolve.comp", defines);
      });
  glUseProgram(program);
  setLightingUniforms(program, params, targets, camera);
  bindGBuffer(frame.gbuffer);
  glBindTextureUnit(LGH_UNIT_PASS_INPUT, targets.accumulation.id());
  glBindImageTexture(LGH_IMAGE_OUTPUT, frame.indirect.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                     GL_RGBA16F);
  glDispatchCompute(groups(targets.width), groups(targets.height), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                  GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
  glUseProgram(0);
}

}  // namespace lgh
