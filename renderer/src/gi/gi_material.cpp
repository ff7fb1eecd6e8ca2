#include "gi/gi_material.hpp"

#include <tuple>

namespace lgh {

glm::vec3 emittedRadiance(const Material& material, const glm::vec3& emissiveTextureMean) {
  const glm::vec3 texture = material.emissiveTexture.valid() ? emissiveTextureMean : glm::vec3(1);
  return glm::max(material.emissiveFactor * texture, glm::vec3(0.0F));
}

bool sameForLightPaths(const Material& a, const Material& b) {
  const auto texture = [](const TextureRef& t) {
    return std::tie(t.image, t.texCoord, t.sampler.wrapS, t.sampler.wrapT);
  };
  return isClassicModel(a.model) == isClassicModel(b.model) &&
         a.baseColorFactor == b.baseColorFactor &&
         texture(a.baseColorTexture) == texture(b.baseColorTexture) &&
         a.metallicFactor == b.metallicFactor && a.roughnessFactor == b.roughnessFactor &&
         a.doubleSided == b.doubleSided && a.emissiveFactor == b.emissiveFactor &&
         a.emissiveTexture.image == b.emissiveTexture.image;
}

GiMaterialGpu packGiMaterial(const Material& material, int baseColorLayer,
                             const glm::vec3& emissiveTextureMean) {
  GiMaterialGpu packed;
  packed.baseColorFactor = material.baseColorFactor;
  packed.emission = glm::vec4(emittedRadiance(material, emissiveTextureMean), 0.0F);
  // The lecture's models have no metallic factor: their `diffuse` colour is all diffuse, as in
  // gbuffer.frag (a glTF default metallic factor of 1 would otherwise make them reflect nothing).
  const float metallic = isClassicModel(material.model) ? 0.0F : material.metallicFactor;
  packed.params =
      glm::vec4(metallic, material.roughnessFactor, material.doubleSided ? 1.0F : 0.0F, 0.0F);
  const TextureRef& texture = material.baseColorTexture;
  if (baseColorLayer >= 0) {
    packed.baseColorTexture = glm::ivec4(baseColorLayer, texture.texCoord == 1 ? 1 : 0,
                                         texture.sampler.wrapS, texture.sampler.wrapT);
  }
  return packed;
}

}  // namespace lgh
