#include "passes/lgh_compute_lighting_pass.hpp"

#include <fmt/format.h>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "passes/direct_lighting_pass.hpp"

namespace lgh {
namespace {

constexpr int kBlock = 8;  // pixels per side of a work group (TILE in the shader)

GLuint blocks(int pixels) { return static_cast<GLuint>((pixels + kBlock - 1) / kBlock); }

}  // namespace

void LghComputeLightingPass::run(const LghHierarchyBuffers& hierarchy,
                                 const LghLightingParams& params, const CameraMatrices& camera,
                                 FrameTargets& frame, LghLightingTargets& targets) {
  const bool direct = targets.interleave == 1;
  std::string defines = fmt::format("#define LGH_SAMPLES {}\n", params.samples);
  if (direct) defines += "#define LGH_DIRECT_OUTPUT 1\n";
  if (params.overdraw) defines += "#define LGH_OVERDRAW 1\n";
  defines += params.brdf.defines();
  const GLuint program = programs_.get(defines, [](const std::string& text) {
    return gl::buildComputeProgram("lgh_lighting.comp", text);
  });
  glUseProgram(program);
  setLightingUniforms(program, params, targets, camera);
  bindHierarchy(hierarchy);
  bindGBuffer(frame.gbuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_SAMPLES, targets.shadowSamples.id());
  glBindImageTexture(LGH_IMAGE_RESERVOIR_SUM, targets.reservoirSum.id(), 0, GL_FALSE, 0,
                     GL_READ_WRITE, GL_R32F);
  glBindImageTexture(LGH_IMAGE_OVERDRAW, targets.overdraw.id(), 0, GL_FALSE, 0, GL_READ_WRITE,
                     GL_R32UI);
  if (direct) {
    glBindImageTexture(LGH_IMAGE_OUTPUT, frame.indirect.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                       GL_RGBA16F);
  } else {
    glBindImageTexture(LGH_IMAGE_OUTPUT, targets.accumulation.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                       GL_RGBA32F);
  }
  const int tiles = targets.interleave * targets.interleave;
  glDispatchCompute(blocks(targets.tileWidth), blocks(targets.tileHeight),
                    static_cast<GLuint>(tiles));
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                  GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
  glUseProgram(0);
}

}  // namespace lgh
