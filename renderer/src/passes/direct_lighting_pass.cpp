#include "passes/direct_lighting_pass.hpp"

#include <array>

#include <glm/gtc/type_ptr.hpp>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"

namespace lgh {

void bindGBuffer(const GBufferTargets& gbuffer) {
  const std::array<GLuint, 5> textures{gbuffer.position.id(), gbuffer.normal.id(),
                                       gbuffer.albedo.id(), gbuffer.material.id(),
                                       gbuffer.emissive.id()};
  glBindTextures(0, static_cast<GLsizei>(textures.size()), textures.data());
  glBindTextureUnit(LGH_UNIT_GBUFFER_LAYERS, gbuffer.layers.id());
}

DirectLightingPass::DirectLightingPass()
    : program_(gl::buildProgram(
          {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "direct_lighting.frag"}})) {}

void DirectLightingPass::run(const DirectLightingInputs& inputs, const CameraMatrices& camera,
                             FrameTargets& targets) {
  glBindFramebuffer(GL_FRAMEBUFFER, targets.directFramebuffer.id());
  glViewport(0, 0, targets.width, targets.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = program_.id();
  glUseProgram(program);
  glProgramUniform1i(program, glGetUniformLocation(program, "uLightCount"), inputs.lightCount);
  glProgramUniform1i(program, glGetUniformLocation(program, "uFrameWidth"), targets.width);
  setShadowRayUniforms(program, inputs.shadows);
  glProgramUniform3fv(program, glGetUniformLocation(program, "uCameraPosition"), 1,
                      glm::value_ptr(camera.position));
  glProgramUniform1f(program, glGetUniformLocation(program, "uAmbient"), inputs.ambient);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_LIGHTS, inputs.lights);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_RAY_VISIBILITY, inputs.visibility);
  bindGBuffer(targets.gbuffer);
  glBindVertexArray(emptyVertexArray_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

}  // namespace lgh
