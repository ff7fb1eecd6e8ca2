#include "passes/gbuffer_pass.hpp"

#include <array>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/shader_library.hpp"

namespace lgh {
namespace {

const Material& materialOrDefault(const Scene& scene, int index) {
  static const Material fallback{};
  if (index < 0 || static_cast<size_t>(index) >= scene.materials.size()) return fallback;
  return scene.materials[static_cast<size_t>(index)];
}

// MATERIAL_LAYER_* bits of glsl/include/material_models.glsl.
GLuint materialLayers(const Material& m) {
  GLuint layers = 0;
  if (m.clearcoat.factor > 0.0F) layers |= 1U;
  if (m.sheen.colorFactor != glm::vec3(0.0F)) layers |= 2U;
  const bool specular = m.specular.factor != 1.0F || m.specular.colorFactor != glm::vec3(1.0F) ||
                        m.specular.ior != 1.5F || m.specular.texture.valid() ||
                        m.specular.colorTexture.valid();
  if (specular) layers |= 4U;
  if (m.transmission.factor > 0.0F) layers |= 8U;
  return layers;
}

// KHR_materials_ior: F0 of the dielectric base; ior 0 means F0 = 1.
float dielectricF0(float ior) {
  if (ior == 0.0F) return 1.0F;
  const float r = (ior - 1.0F) / (ior + 1.0F);
  return r * r;
}

gl::Program buildGBufferProgram(const char* geometryShader) {
  if (geometryShader == nullptr) {
    return gl::buildProgram(
        {{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "gbuffer.frag"}});
  }
  return gl::buildProgram({{GL_VERTEX_SHADER, "gbuffer.vert"},
                           {GL_GEOMETRY_SHADER, geometryShader},
                           {GL_FRAGMENT_SHADER, "gbuffer.frag"}});
}

}  // namespace

GBufferPass::GBufferPass()
    : programs_{buildGBufferProgram(nullptr), buildGBufferProgram("gbuffer_lines.geom"),
                buildGBufferProgram("gbuffer_points.geom")} {}

GLuint GBufferPass::programFor(Topology topology) const {
  return programs_[static_cast<std::size_t>(topology)].id();
}

void GBufferPass::setMaterial(GLuint program, const Scene& scene, const GpuScene& gpuScene,
                              int materialIndex, bool unlit) {
  const Material& material = materialOrDefault(scene, materialIndex);
  auto location = [program](const char* name) { return glGetUniformLocation(program, name); };
  GLuint textureMask = 0;
  GLuint texCoord1Mask = 0;
  std::array<glm::mat3x2, kMaterialTextureSlots> transforms{};
  const auto slots = materialTextureSlots(material);
  for (GLuint slot = 0; slot < slots.size(); ++slot) {
    const TextureRef& ref = *slots[slot].texture;
    auto bound = gpuScene.texture(ref, slots[slot].srgb);
    glBindTextureUnit(slot, bound.texture);
    glBindSampler(slot, bound.sampler);
    if (bound.texture != 0) textureMask |= 1U << slot;
    if (ref.texCoord == 1) texCoord1Mask |= 1U << slot;
    transforms[slot] = ref.transform.matrix();
  }
  glProgramUniform1ui(program, location("uTextureMask"), textureMask);
  glProgramUniform1ui(program, location("uTexCoord1Mask"), texCoord1Mask);
  glProgramUniformMatrix3x2fv(program, location("uUvTransform"),
                              static_cast<GLsizei>(transforms.size()), GL_FALSE,
                              glm::value_ptr(transforms[0]));
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
  const MaterialModel model = unlit ? MaterialModel::Unlit : material.model;
  glProgramUniform1ui(program, location("uModel"), static_cast<GLuint>(model));
  glProgramUniform1ui(program, location("uLayers"), materialLayers(material));
  glProgramUniform3f(program, location("uClearcoat"), material.clearcoat.factor,
                     material.clearcoat.roughness, material.clearcoat.normalScale);
  glProgramUniform4f(program, location("uSheen"), material.sheen.colorFactor.r,
                     material.sheen.colorFactor.g, material.sheen.colorFactor.b,
                     material.sheen.roughnessFactor);
  glProgramUniform4f(program, location("uSpecular"), material.specular.colorFactor.r,
                     material.specular.colorFactor.g, material.specular.colorFactor.b,
                     material.specular.factor);
  glProgramUniform1f(program, location("uDielectricF0"), dielectricF0(material.specular.ior));
  glProgramUniform1f(program, location("uTransmission"), material.transmission.factor);
  const glm::vec3 tint = material.transmission.tint();
  glProgramUniform3fv(program, location("uTransmissionTint"), 1, glm::value_ptr(tint));
}

void GBufferPass::setFrameUniforms(GLuint program, const CameraMatrices& camera,
                                   const PrimitiveSettings& primitives, const FrameTargets& targets,
                                   bool disk) {
  auto location = [program](const char* name) { return glGetUniformLocation(program, name); };
  glProgramUniformMatrix4fv(program, location("uViewProjection"), 1, GL_FALSE,
                            glm::value_ptr(camera.viewProjection()));
  glProgramUniform3fv(program, location("uCameraPosition"), 1, glm::value_ptr(camera.position));
  glProgramUniform2f(program, location("uViewportSize"), static_cast<float>(targets.width),
                     static_cast<float>(targets.height));
  glProgramUniform1f(program, location("uLineWidth"), primitives.lineWidth);
  glProgramUniform1f(program, location("uPointSize"), primitives.pointSize);
  glProgramUniform1i(program, location("uPointDisk"), disk ? 1 : 0);
}

void GBufferPass::run(const Scene& scene, const GpuScene& gpuScene, const CameraMatrices& camera,
                      const PrimitiveSettings& primitives, FrameTargets& targets) {
  glBindFramebuffer(GL_FRAMEBUFFER, targets.gbuffer.framebuffer.id());
  glViewport(0, 0, targets.width, targets.height);
  const std::array<float, 4> zero{0, 0, 0, 0};
  for (GLint i = 0; i < 5; ++i) glClearBufferfv(GL_COLOR, i, zero.data());
  const std::array<GLuint, 4> zeroBits{0, 0, 0, 0};
  glClearBufferuiv(GL_COLOR, 5, zeroBits.data());
  const float farDepth = 1.0F;
  glClearBufferfv(GL_DEPTH, 0, &farDepth);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glEnable(GL_FRAMEBUFFER_SRGB);  // the albedo target is sRGB-encoded
  glCullFace(GL_BACK);
  for (std::size_t t = 0; t < programs_.size(); ++t) {
    const bool disk =
        static_cast<Topology>(t) == Topology::Points && primitives.pointShape == PointShape::Disk;
    setFrameUniforms(programs_[t].id(), camera, primitives, targets, disk);
  }
  GLuint currentProgram = 0;
  int currentMaterial = -2;
  bool currentUnlit = false;
  for (const auto& item : gpuScene.drawItems()) {
    const GLuint program = programFor(item.topology);
    if (program != currentProgram) {
      glUseProgram(program);
      currentProgram = program;
      currentMaterial = -2;
    }
    if (item.material != currentMaterial || item.unlit != currentUnlit) {
      setMaterial(program, scene, gpuScene, item.material, item.unlit);
      currentMaterial = item.material;
      currentUnlit = item.unlit;
    }
    // Widened lines and points are quads of either winding: never culled.
    const bool cull = item.topology == Topology::Triangles &&
                      !materialOrDefault(scene, item.material).doubleSided;
    if (cull) {
      glEnable(GL_CULL_FACE);
    } else {
      glDisable(GL_CULL_FACE);
    }
    // Mirrored instances flip the winding; keep back-face culling right for them.
    glFrontFace(glm::determinant(glm::mat3(item.world)) < 0.0F ? GL_CW : GL_CCW);
    const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(item.world));
    glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "uWorld"), 1, GL_FALSE,
                              glm::value_ptr(item.world));
    glProgramUniformMatrix3fv(program, glGetUniformLocation(program, "uNormalMatrix"), 1, GL_FALSE,
                              glm::value_ptr(normalMatrix));
    glBindVertexArray(item.vertexArray);
    const GLenum mode = item.topology == Topology::Triangles ? GL_TRIANGLES
                        : item.topology == Topology::Lines   ? GL_LINES
                                                             : GL_POINTS;
    glDrawElements(mode, item.indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glFrontFace(GL_CCW);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_FRAMEBUFFER_SRGB);
  for (GLuint slot = 0; slot < kMaterialTextureSlots; ++slot) glBindSampler(slot, 0);
}

}  // namespace lgh
