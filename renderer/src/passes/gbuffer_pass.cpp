#include "passes/gbuffer_pass.hpp"

#include <array>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/shader_library.hpp"

namespace lgh {
namespace {

enum TextureSlot : GLuint { BaseColor = 0, MetallicRoughness, Normal, Occlusion, Emissive };

const Material& materialOrDefault(const Scene& scene, int index) {
  static const Material fallback{};
  if (index < 0 || static_cast<size_t>(index) >= scene.materials.size()) return fallback;
  return scene.materials[static_cast<size_t>(index)];
}

}  // namespace

GBufferPass::GBufferPass()
    : program_(gl::buildProgram(
          {{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "gbuffer.frag"}})) {
  worldLocation_ = glGetUniformLocation(program_.id(), "uWorld");
  normalMatrixLocation_ = glGetUniformLocation(program_.id(), "uNormalMatrix");
  viewProjectionLocation_ = glGetUniformLocation(program_.id(), "uViewProjection");
}

void GBufferPass::setMaterial(const Scene& scene, const GpuScene& gpuScene, int materialIndex) {
  const Material& material = materialOrDefault(scene, materialIndex);
  const GLuint program = program_.id();
  auto location = [program](const char* name) { return glGetUniformLocation(program, name); };
  const std::array<std::pair<const TextureRef*, bool>, 5> slots{{
      {&material.baseColorTexture, true},
      {&material.metallicRoughnessTexture, false},
      {&material.normalTexture, false},
      {&material.occlusionTexture, false},
      {&material.emissiveTexture, true},
  }};
  GLuint textureMask = 0;
  GLuint texCoord1Mask = 0;
  for (GLuint slot = 0; slot < slots.size(); ++slot) {
    auto bound = gpuScene.texture(*slots[slot].first, slots[slot].second);
    glBindTextureUnit(slot, bound.texture);
    glBindSampler(slot, bound.sampler);
    if (bound.texture != 0) textureMask |= 1U << slot;
    if (slots[slot].first->texCoord == 1) texCoord1Mask |= 1U << slot;
  }
  glProgramUniform1ui(program, location("uTextureMask"), textureMask);
  glProgramUniform1ui(program, location("uTexCoord1Mask"), texCoord1Mask);
  glProgramUniform4fv(program, location("uBaseColorFactor"), 1,
                      glm::value_ptr(material.baseColorFactor));
  glProgramUniform1f(program, location("uMetallicFactor"), material.metallicFactor);
  glProgramUniform1f(program, location("uRoughnessFactor"), material.roughnessFactor);
  glProgramUniform3fv(program, location("uEmissiveFactor"), 1,
                      glm::value_ptr(material.emissiveFactor));
  glProgramUniform1f(program, location("uNormalScale"), material.normalScale);
  glProgramUniform1f(program, location("uOcclusionStrength"), material.occlusionStrength);
  glProgramUniform1f(program, location("uAlphaCutoff"),
                     material.alphaMode == AlphaMode::Mask ? material.alphaCutoff : -1.0F);
  if (material.doubleSided) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
  }
}

void GBufferPass::run(const Scene& scene, const GpuScene& gpuScene, const CameraMatrices& camera,
                      FrameTargets& targets) {
  glBindFramebuffer(GL_FRAMEBUFFER, targets.gbuffer.framebuffer.id());
  glViewport(0, 0, targets.width, targets.height);
  const std::array<float, 4> zero{0, 0, 0, 0};
  for (GLint i = 0; i < 5; ++i) glClearBufferfv(GL_COLOR, i, zero.data());
  const float farDepth = 1.0F;
  glClearBufferfv(GL_DEPTH, 0, &farDepth);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glEnable(GL_FRAMEBUFFER_SRGB);  // the albedo target is sRGB-encoded
  glCullFace(GL_BACK);
  glUseProgram(program_.id());
  glProgramUniformMatrix4fv(program_.id(), viewProjectionLocation_, 1, GL_FALSE,
                            glm::value_ptr(camera.viewProjection()));
  glProgramUniform3fv(program_.id(), glGetUniformLocation(program_.id(), "uCameraPosition"), 1,
                      glm::value_ptr(camera.position));
  int currentMaterial = -2;
  for (const auto& item : gpuScene.drawItems()) {
    if (item.material != currentMaterial) {
      setMaterial(scene, gpuScene, item.material);
      currentMaterial = item.material;
    }
    // Mirrored instances flip the winding; keep back-face culling right for them.
    glFrontFace(glm::determinant(glm::mat3(item.world)) < 0.0F ? GL_CW : GL_CCW);
    const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(item.world));
    glProgramUniformMatrix4fv(program_.id(), worldLocation_, 1, GL_FALSE,
                              glm::value_ptr(item.world));
    glProgramUniformMatrix3fv(program_.id(), normalMatrixLocation_, 1, GL_FALSE,
                              glm::value_ptr(normalMatrix));
    glBindVertexArray(item.vertexArray);
    glDrawElements(GL_TRIANGLES, item.indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glFrontFace(GL_CCW);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_FRAMEBUFFER_SRGB);
  for (GLuint slot = 0; slot < 5; ++slot) glBindSampler(slot, 0);
}

}  // namespace lgh
