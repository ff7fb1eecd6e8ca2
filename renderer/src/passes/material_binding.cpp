#include "passes/material_binding.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string_view>

#include <glm/gtc/type_ptr.hpp>

#include "passes/brdf_features.hpp"

namespace lgh {
namespace {

// KHR_materials_ior: F0 of the dielectric base; ior 0 means F0 = 1.
float dielectricF0(float ior) {
  if (ior == 0.0F) return 1.0F;
  const float r = (ior - 1.0F) / (ior + 1.0F);
  return r * r;
}

// The classic model's exponent and specular colour (Cook-Torrance: F0).
float modelExponent(const Material& m, MaterialModel model) {
  switch (model) {
    case MaterialModel::OrenNayar:
      return m.classic.sigma;
    case MaterialModel::CookTorrance:
      return m.classic.m;
    default:
      return m.classic.shininess;
  }
}

glm::vec3 modelSpecular(const Material& m, MaterialModel model) {
  return model == MaterialModel::CookTorrance ? m.classic.f0 : m.classic.specular;
}

// Sets a program's uniforms, skipping each whose value is the one it already holds
// (gl::UniformLocations::changed).
class Uniforms {
 public:
  explicit Uniforms(gl::UniformLocations& locations) : locations_(locations) {}
  GLuint program() const { return locations_.program(); }
  void set(std::string_view name, float v) const {
    if (const auto at = locations_.changed(name, v)) glProgramUniform1f(program(), *at, v);
  }
  void set(std::string_view name, int v) const {
    if (const auto at = locations_.changed(name, v)) glProgramUniform1i(program(), *at, v);
  }
  void set(std::string_view name, GLuint v) const {
    if (const auto at = locations_.changed(name, v)) glProgramUniform1ui(program(), *at, v);
  }
  void set(std::string_view name, bool v) const { set(name, v ? 1 : 0); }
  void set(std::string_view name, const glm::vec2& v) const {
    if (const auto at = locations_.changed(name, v)) {
      glProgramUniform2fv(program(), *at, 1, glm::value_ptr(v));
    }
  }
  void set(std::string_view name, const glm::vec3& v) const {
    if (const auto at = locations_.changed(name, v)) {
      glProgramUniform3fv(program(), *at, 1, glm::value_ptr(v));
    }
  }
  void set(std::string_view name, const glm::vec4& v) const {
    if (const auto at = locations_.changed(name, v)) {
      glProgramUniform4fv(program(), *at, 1, glm::value_ptr(v));
    }
  }
  void set(std::string_view name, const glm::mat4& v) const {
    if (const auto at = locations_.changed(name, v)) {
      glProgramUniformMatrix4fv(program(), *at, 1, GL_FALSE, glm::value_ptr(v));
    }
  }
  void set(std::string_view name, const glm::mat3& v) const {
    if (const auto at = locations_.changed(name, v)) {
      glProgramUniformMatrix3fv(program(), *at, 1, GL_FALSE, glm::value_ptr(v));
    }
  }
  template <std::size_t N>
  void set(std::string_view name, const std::array<glm::mat3x2, N>& v) const {
    if (const auto at = locations_.changed(name, v)) {
      glProgramUniformMatrix3x2fv(program(), *at, static_cast<GLsizei>(N), GL_FALSE,
                                  glm::value_ptr(v[0]));
    }
  }

 private:
  gl::UniformLocations& locations_;
};

// Binds units [first, last] of `textures` and `samplers` where they differ from `state`'s.
void bindChangedUnits(const std::array<GLuint, kMaterialTextureSlots>& textures,
                      const std::array<GLuint, kMaterialTextureSlots>& samplers,
                      SurfaceDrawState& state) {
  std::size_t first = kMaterialTextureSlots;
  std::size_t last = 0;
  for (std::size_t unit = 0; unit < kMaterialTextureSlots; ++unit) {
    if (!state.texturesKnown || textures[unit] != state.textures[unit] ||
        samplers[unit] != state.samplers[unit]) {
      first = std::min(first, unit);
      last = unit;
    }
  }
  if (first == kMaterialTextureSlots) return;
  // GL 4.4's multi-bind: the changed units in one call each instead of two calls per unit.
  const auto count = static_cast<GLsizei>(last - first + 1);
  glBindTextures(static_cast<GLuint>(first), count, &textures[first]);
  glBindSamplers(static_cast<GLuint>(first), count, &samplers[first]);
  state.textures = textures;
  state.samplers = samplers;
  state.texturesKnown = true;
}

void bindTextures(const Uniforms& u, const Material& material, GpuScene& gpu,
                  SurfaceDrawState& state) {
  GLuint textureMask = 0;
  GLuint texCoord1Mask = 0;
  GLuint twoChannelMask = 0;
  std::array<glm::mat3x2, kMaterialTextureSlots> transforms{};
  std::array<GLuint, kMaterialTextureSlots> textures{};
  std::array<GLuint, kMaterialTextureSlots> samplers{};
  const auto slots = materialTextureSlots(material);
  for (GLuint slot = 0; slot < slots.size(); ++slot) {
    const TextureRef& ref = *slots[slot].texture;
    const GpuScene::BoundTexture bound = gpu.texture(ref, slots[slot].usage);
    textures[slot] = bound.texture;
    samplers[slot] = bound.sampler;
    if (bound.texture != 0) textureMask |= 1U << slot;
    if (bound.twoChannel) twoChannelMask |= 1U << slot;
    if (ref.texCoord == 1) texCoord1Mask |= 1U << slot;
    transforms[slot] = ref.transform.matrix();
  }
  bindChangedUnits(textures, samplers, state);
  u.set("uTextureMask", textureMask);
  u.set("uTexCoord1Mask", texCoord1Mask);
  u.set("uTwoChannelMask", twoChannelMask);
  u.set("uUvTransform", transforms);
}

void setSurfaceDetail(const Uniforms& u, const SurfaceDetailMaterial& s) {
  u.set("uSurface", static_cast<GLuint>(s.technique));
  u.set("uHeightScale", s.heightScale);
  u.set("uParallaxBias", s.parallaxBias.value_or(s.heightScale * 0.5F));
  u.set("uReliefLinearSteps", s.reliefLinearSteps);
  u.set("uReliefBinarySteps", s.reliefBinarySteps);
  u.set("uReliefSelfShadow", s.reliefSelfShadow);
  u.set("uReliefSilhouettes", s.reliefSilhouettes);
  u.set("uTessellationPixels", s.tessellationPixels);
}

}  // namespace

MaterialModel effectiveModel(const Material& material, bool unlit) {
  return unlit ? MaterialModel::Unlit : material.model;
}

std::uint32_t materialFeatures(const Material& material, const GpuScene::DrawItem& item) {
  const MaterialModel model = effectiveModel(material, item.unlit);
  const SurfaceDetailMaterial& surface = material.surface;
  std::uint32_t features = 0U;
  const bool silhouettes = surface.usesHeight() && surface.technique == SurfaceDetail::Relief &&
                           surface.reliefSilhouettes;
  if (material.alphaMode == AlphaMode::Mask || silhouettes || item.topology == Topology::Points) {
    features |= kMaterialDiscard;
  }
  if (surface.usesHeight()) features |= kMaterialHeight;
  if (model == MaterialModel::MetallicRoughness && materialLayerBits(material) != 0U) {
    features |= kMaterialLayers;
  }
  if (isClassicModel(model)) features |= kMaterialClassic;
  if (material.bicubic) features |= kMaterialBicubic;
  const auto textures = allMaterialTextures(material);
  const bool textured = std::any_of(textures.begin(), textures.end(),
                                    [](const TextureRef* texture) { return texture->valid(); });
  if (textured || (features & kMaterialLayers) != 0U) features |= kMaterialSurfaceFrame;
  return features;
}

bool displacedMaterial(const Material& material) {
  return material.surface.technique == SurfaceDetail::Displacement &&
         material.surface.heightTexture.valid();
}

SurfaceProgramKey surfaceProgramKey(const Material& material, const GpuScene::DrawItem& item,
                                    bool forward) {
  SurfaceProgramKey key;
  key.topology = item.topology;
  key.forward = forward;
  if (!forward) key.features = materialFeatures(material, item);
  if (item.topology != Topology::Triangles) return key;
  if (isClassicModel(effectiveModel(material, item.unlit))) key.shading = material.classic.shading;
  key.displaced = displacedMaterial(material);
  return key;
}

void bindMaterial(SurfaceProgram& program, const Material& material, GpuScene& gpuScene, bool unlit,
                  SurfaceDrawState& state) {
  const Uniforms u(program.uniforms);
  bindTextures(u, material, gpuScene, state);
  const MaterialModel model = effectiveModel(material, unlit);
  u.set("uBaseColorFactor", material.baseColorFactor);
  u.set("uMetallicFactor", material.metallicFactor);
  u.set("uRoughnessFactor", material.roughnessFactor);
  u.set("uEmissiveFactor", material.emissiveFactor);
  u.set("uNormalScale", material.normalScale);
  u.set("uOcclusionStrength", material.occlusionStrength);
  u.set("uAlphaCutoff", material.alphaMode == AlphaMode::Mask ? material.alphaCutoff : -1.0F);
  u.set("uModel", static_cast<GLuint>(model));
  u.set("uLayers", model == MaterialModel::MetallicRoughness ? materialLayerBits(material) : 0U);
  const Clearcoat& cc = material.clearcoat;
  u.set("uClearcoat", glm::vec3(cc.factor, cc.roughness, cc.normalScale));
  u.set("uSheen", glm::vec4(material.sheen.colorFactor, material.sheen.roughnessFactor));
  u.set("uSpecular", glm::vec4(material.specular.colorFactor, material.specular.factor));
  u.set("uDielectricF0", dielectricF0(material.specular.ior));
  u.set("uTransmission", material.transmission.factor);
  u.set("uTransmissionTint", material.transmission.tint());
  u.set("uAmbientColor", material.classic.ambient.value_or(glm::vec3(0.0F)));
  u.set("uAmbientIsDiffuse", !material.classic.ambient.has_value());
  u.set("uSpecularColor", modelSpecular(material, model));
  u.set("uExponent", modelExponent(material, model));
  u.set("uShading",
        static_cast<GLuint>(isClassicModel(model) ? material.classic.shading : ShadingMode::Pixel));
  u.set("uBicubic", material.bicubic);
  u.set("uLightMapStrength", material.lightMapStrength);
  setSurfaceDetail(u, material.surface);
}

void setSurfaceFrameUniforms(SurfaceProgram& program, const SurfaceFrame& frame, bool pointDisk) {
  const Uniforms u(program.uniforms);
  u.set("uViewProjection", frame.camera->viewProjection());
  u.set("uCameraPosition", frame.camera->position);
  u.set("uViewportSize",
        glm::vec2(static_cast<float>(frame.width), static_cast<float>(frame.height)));
  u.set("uLineWidth", frame.primitives->lineWidth);
  u.set("uPointSize", frame.primitives->pointSize);
  u.set("uPointDisk", pointDisk);
  u.set("uLightCount", frame.lightCount);
  u.set("uAmbient", frame.ambient);
  u.set("uTessellationMaxLevel", frame.maxTessellationLevel);
}

void drawSurface(SurfaceProgram& program, const GpuScene::DrawItem& item, const Material& material,
                 bool displaced, SurfaceDrawState& state) {
  // Widened lines and points are quads of either winding: never culled.
  const int cull = item.topology == Topology::Triangles && !material.doubleSided ? 1 : 0;
  if (cull != state.cull) {
    if (cull == 1) {
      glEnable(GL_CULL_FACE);
    } else {
      glDisable(GL_CULL_FACE);
    }
    state.cull = cull;
  }
  // Mirrored instances flip the winding; keep back-face culling right for them.
  const GLenum frontFace = item.mirrored ? GL_CW : GL_CCW;
  if (frontFace != state.frontFace) {
    glFrontFace(frontFace);
    state.frontFace = frontFace;
  }
  // The item's transforms come from the vertex array's per-draw attributes (its base instance).
  const Uniforms u(program.uniforms);
  u.set("uHasTangents", item.tangents);
  if (item.vertexArray != state.vertexArray) {
    glBindVertexArray(item.vertexArray);
    state.vertexArray = item.vertexArray;
  }
  GLenum mode = GL_TRIANGLES;
  if (item.topology == Topology::Lines) mode = GL_LINES;
  if (item.topology == Topology::Points) mode = GL_POINTS;
  if (displaced) {
    glPatchParameteri(GL_PATCH_VERTICES, 3);
    mode = GL_PATCHES;
  }
  const auto firstByte = static_cast<std::uintptr_t>(item.firstIndex) * sizeof(std::uint32_t);
  glDrawElementsInstancedBaseVertexBaseInstance(
      mode, item.indexCount, GL_UNSIGNED_INT,
      reinterpret_cast<const void*>(firstByte),  // NOLINT: GL's offset type
      1, item.baseVertex, item.drawIndex);
}

void unbindMaterialSamplers() {
  for (GLuint slot = 0; slot < kMaterialTextureSlots; ++slot) glBindSampler(slot, 0);
}

}  // namespace lgh
