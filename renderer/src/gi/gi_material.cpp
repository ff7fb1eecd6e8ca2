#include "gi/gi_material.hpp"

namespace lgh {

glm::vec3 emittedRadiance(const Material& material, const glm::vec3& emissiveTextureMean) {
  const glm::vec3 texture = material.emissiveTexture.valid() ? emissiveTextureMean : glm::vec3(1);
  return glm::max(material.emissiveFactor * texture, glm::vec3(0.0F));
}

GiMaterialGpu packGiMaterial(const Material& material, int baseColorLayer,
                             const glm::vec3& emissiveTextureMean) {
  GiMaterialGpu packed;
  packed.baseColorFactor = material.baseColorFactor;
  packed.emission = glm::vec4(emittedRadiance(material, emissiveTextureMean), 0.0F);
  packed.params = glm::vec4(material.metallicFactor, material.roughnessFactor,
                            material.doubleSided ? 1.0F : 0.0F, 0.0F);
  const TextureRef& texture = material.baseColorTexture;
  if (baseColorLayer >= 0) {
    packed.baseColorTexture = glm::ivec4(baseColorLayer, texture.texCoord == 1 ? 1 : 0,
                                         texture.sampler.wrapS, texture.sampler.wrapT);
  }
  return packed;
}

}  // namespace lgh
