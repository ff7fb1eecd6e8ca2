// Materials and textures: glTF metallic-roughness materials -> lgh::Material, with factors
// clamped to their ranges, KHR_materials_emissive_strength applied, and each texture resolved to
// its decoded image (moved into Scene::images on first use) and sampler. An image a material uses
// must have loaded; one that no material uses and that failed is dropped with a warning.
#pragma once

#include <map>
#include <string>

#include <glm/glm.hpp>

#include "lgh/error.hpp"
#include "scene/gltf/load_context.hpp"
#include "scene/gltf/tinygltf.hpp"
#include "scene/scene.hpp"

namespace lgh::gltf {

// `value` as a float, or `fallback` when it is not finite.
float finiteOr(double value, float fallback);

class MaterialConverter {
 public:
  // Decoded images move from ctx.images into scene.images as materials use them.
  MaterialConverter(const tinygltf::Model& model, LoadContext& ctx, Scene& scene);

  Material convert(int index);

  // Images that failed to load but that no material used: dropped, with a warning.
  void warnAboutUnusedFailures();

 private:
  // emissiveFactor, times KHR_materials_emissive_strength's emissiveStrength when present.
  glm::vec3 emissive(const tinygltf::Material& source) const;

  AlphaMode alphaMode(const std::string& mode, const std::string& owner) const;

  TextureRef texture(int textureIndex, int texCoord, const std::string& owner);

  Sampler sampler(int index, const std::string& owner) const;

  // The Scene::images index of glTF image `index`, moving the decoded image over on first use.
  int sceneImage(int index);

  // tinygltf keeps an external image it could not read as a bare URI; say why it is missing.
  Error missingImageError(int index) const;

  const tinygltf::Model& model_;
  LoadContext& ctx_;
  Scene& scene_;
  std::map<int, int> imageRemap_;
};

}  // namespace lgh::gltf
