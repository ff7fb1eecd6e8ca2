#include "passes/direct_lighting_pass.hpp"

#include <array>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "passes/composite_pass.hpp"
#include "passes/light_loops.hpp"

namespace lgh {

void bindGBuffer(const GBufferTargets& gbuffer) {
  const std::array<GLuint, 5> textures{gbuffer.position.id(), gbuffer.normal.id(),
                                       gbuffer.albedo.id(), gbuffer.material.id(),
                                       gbuffer.emissive.id()};
  glBindTextures(0, static_cast<GLsizei>(textures.size()), textures.data());
  glBindTextureUnit(LGH_UNIT_GBUFFER_LAYERS, gbuffer.layers.id());
}

GLuint DirectLightingPass::program(const DirectLightingInputs& inputs,
                                   const std::optional<OutputPixels>& finalOutput) {
  std::string defines = inputs.brdf.defines();
  if (unrollsLightLoops_) {
    defines += lightCountDefines(inputs.lightCount) + shadowLayoutDefines(inputs.shadows);
  }
  ProgramKey key{std::move(defines), finalOutput};
  auto it = programs_.find(key);
  if (it == programs_.end()) {
    gl::Program program =
        finalOutput
            ? buildFrameOutputProgram("direct_lighting.comp",
                                      key.first + "#define LGH_FINAL_OUTPUT 1\n", *finalOutput)
            : gl::buildComputeProgram("direct_lighting.comp", key.first);
    it = programs_.emplace(std::move(key), std::move(program)).first;
  }
  return it->second.id();
}

void DirectLightingPass::run(const DirectLightingInputs& inputs, const CameraMatrices& camera,
                             FrameTargets& targets) {
  const GLuint program = this->program(inputs, std::nullopt);
  glBindImageTexture(LGH_IMAGE_OUTPUT, targets.direct.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                     GL_RGBA16F);
  dispatch(program, inputs, camera, targets, allTiles(targets.width, targets.height));
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void DirectLightingPass::runToOutput(const DirectLightingInputs& inputs,
                                     const CameraMatrices& camera, const OutputSettings& output,
                                     OutputPixels pixels, FrameTargets& targets) {
  const GLuint program = this->program(inputs, pixels);
  bindFrameOutput(program, output, pixels, targets, clearsBackground_);
  // Over a cleared output the tiles without a surface have nothing to store.
  dispatch(
      program, inputs, camera, targets,
      clearsBackground_ ? targets.tilesWithSurfaces() : allTiles(targets.width, targets.height));
  // Read next by the pixel pack pass or a read-back, as the composite's output is.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                  GL_PIXEL_BUFFER_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void DirectLightingPass::dispatch(GLuint program, const DirectLightingInputs& inputs,
                                  const CameraMatrices& camera, FrameTargets& targets,
                                  const FrameTiles& tiles) {
  glUseProgram(program);
  glProgramUniform1i(program, glGetUniformLocation(program, "uLightCount"), inputs.lightCount);
  glProgramUniform1i(program, glGetUniformLocation(program, "uFrameWidth"), targets.width);
  glProgramUniform1i(program, glGetUniformLocation(program, "uFrameHeight"), targets.height);
  setShadowRayUniforms(program, inputs.shadows);
  glProgramUniform3fv(program, glGetUniformLocation(program, "uCameraPosition"), 1,
                      glm::value_ptr(camera.position));
  glProgramUniform1f(program, glGetUniformLocation(program, "uAmbient"), inputs.ambient);
  glProgramUniform1i(program, glGetUniformLocation(program, "uHasEmission"),
                     inputs.emission ? 1 : 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_LIGHTS, inputs.lights);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_RAY_VISIBILITY, inputs.visibility);
  bindGBuffer(targets.gbuffer);
  dispatchTiles(program, tiles);
}

}  // namespace lgh
