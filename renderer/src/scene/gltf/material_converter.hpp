// Materials and textures: glTF metallic-roughness materials -> lgh::Material, with factors
// clamped to their ranges, the KHR_materials_* extensions read (material_extensions.cpp), and each
// texture resolved to its decoded image (moved into Scene::images on first use), sampler and
// KHR_texture_transform. A texture's image comes from EXT_texture_webp where the texture names
// one, else from its source. An image a material uses must have loaded; one that no material uses
// and that failed is dropped with a warning.
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

  // `variant`: the KHR_materials_variants variant the request chose (-1: none) decides nothing
  // here; the primitive converter maps materials through it.
  Material convert(int index);

  // A textureInfo given as JSON inside an extension (e.g. clearcoatTexture): index, texCoord,
  // KHR_texture_transform.
  TextureRef textureFromValue(const tinygltf::Value& info, const std::string& owner);

  // Images that failed to load but that no material used: dropped, with a warning.
  void warnAboutUnusedFailures();

  // Scene::textures: every glTF texture (image and sampler) on TEXCOORD_0, for material
  // parameters that name textures by index; an entry whose image failed stays invalid.
  std::vector<TextureRef> allTextures();

 private:
  // emissiveFactor, times KHR_materials_emissive_strength's emissiveStrength when present.
  glm::vec3 emissive(const tinygltf::Material& source) const;

  AlphaMode alphaMode(const std::string& mode, const std::string& owner) const;

  TextureRef texture(int textureIndex, int texCoord, const tinygltf::ExtensionMap& extensions,
                     const std::string& owner);

  // The image a texture samples: MSFT_texture_dds's or EXT_texture_webp's source where given,
  // else `source`; -1 none.
  int textureImage(const tinygltf::Texture& texture) const;

  // KHR_materials_* (clearcoat, sheen, specular, ior, transmission, volume, unlit).
  void readExtensions(const tinygltf::Material& source, const std::string& owner,
                      Material& material);

  // extras.lgh: the lecture's models and techniques, as a request's material parameters
  // (material_extras.cpp). Textures name glTF textures.
  void applyExtras(const tinygltf::Material& source, int index, const std::string& owner,
                   Material& material);

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
