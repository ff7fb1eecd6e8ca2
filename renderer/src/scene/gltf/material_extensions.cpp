// The KHR_materials_* extensions of a glTF material (MaterialConverter::readExtensions): unlit,
// clearcoat, sheen, specular, ior, transmission and volume. Factors are clamped to the ranges
// the extensions give; textures go through the same resolution as the core material's.
#include <algorithm>
#include <string>

#include "scene/gltf/material_converter.hpp"

namespace lgh::gltf {
namespace {

const tinygltf::Value* extension(const tinygltf::Material& source, const char* name) {
  const auto it = source.extensions.find(name);
  return it == source.extensions.end() || !it->second.IsObject() ? nullptr : &it->second;
}

float number(const tinygltf::Value& object, const char* key, float fallback) {
  if (!object.Has(key) || !object.Get(key).IsNumber()) return fallback;
  return finiteOr(object.Get(key).GetNumberAsDouble(), fallback);
}

glm::vec3 color(const tinygltf::Value& object, const char* key, const glm::vec3& fallback) {
  if (!object.Has(key) || !object.Get(key).IsArray() || object.Get(key).ArrayLen() != 3) {
    return fallback;
  }
  glm::vec3 value = fallback;
  for (int c = 0; c < 3; ++c) {
    const tinygltf::Value& element = object.Get(key).Get(c);
    if (element.IsNumber()) value[c] = finiteOr(element.GetNumberAsDouble(), fallback[c]);
  }
  return value;
}

float unit(float value) { return std::clamp(value, 0.0F, 1.0F); }

}  // namespace

void MaterialConverter::readExtensions(const tinygltf::Material& source, const std::string& owner,
                                       Material& material) {
  // Named by JSON pointer, as the core material's textures are.
  auto textureOf = [&](const tinygltf::Value& object, const char* name, const char* key) {
    return object.Has(key)
               ? textureFromValue(object.Get(key), owner + "/extensions/" + name + "/" + key)
               : TextureRef{};
  };
  if (extension(source, "KHR_materials_unlit") != nullptr) material.model = MaterialModel::Unlit;
  if (const tinygltf::Value* cc = extension(source, "KHR_materials_clearcoat")) {
    Clearcoat& coat = material.clearcoat;
    coat.factor = unit(number(*cc, "clearcoatFactor", 0.0F));
    coat.roughness = unit(number(*cc, "clearcoatRoughnessFactor", 0.0F));
    coat.texture = textureOf(*cc, "KHR_materials_clearcoat", "clearcoatTexture");
    coat.roughnessTexture = textureOf(*cc, "KHR_materials_clearcoat", "clearcoatRoughnessTexture");
    coat.normalTexture = textureOf(*cc, "KHR_materials_clearcoat", "clearcoatNormalTexture");
    if (cc->Has("clearcoatNormalTexture")) {
      coat.normalScale = number(cc->Get("clearcoatNormalTexture"), "scale", 1.0F);
    }
  }
  if (const tinygltf::Value* sheen = extension(source, "KHR_materials_sheen")) {
    material.sheen.colorFactor =
        glm::clamp(color(*sheen, "sheenColorFactor", glm::vec3(0.0F)), 0.0F, 1.0F);
    material.sheen.roughnessFactor = unit(number(*sheen, "sheenRoughnessFactor", 0.0F));
    material.sheen.colorTexture = textureOf(*sheen, "KHR_materials_sheen", "sheenColorTexture");
    material.sheen.roughnessTexture =
        textureOf(*sheen, "KHR_materials_sheen", "sheenRoughnessTexture");
  }
  if (const tinygltf::Value* specular = extension(source, "KHR_materials_specular")) {
    material.specular.factor = unit(number(*specular, "specularFactor", 1.0F));
    material.specular.colorFactor =
        glm::max(color(*specular, "specularColorFactor", glm::vec3(1.0F)), 0.0F);
    material.specular.texture = textureOf(*specular, "KHR_materials_specular", "specularTexture");
    material.specular.colorTexture =
        textureOf(*specular, "KHR_materials_specular", "specularColorTexture");
  }
  if (const tinygltf::Value* ior = extension(source, "KHR_materials_ior")) {
    // ior 0 is the extension's way of saying "infinitely reflective" (F0 = 1); otherwise >= 1.
    const float value = number(*ior, "ior", 1.5F);
    material.specular.ior = value == 0.0F ? 0.0F : std::max(value, 1.0F);
  }
  if (const tinygltf::Value* transmission = extension(source, "KHR_materials_transmission")) {
    material.transmission.factor = unit(number(*transmission, "transmissionFactor", 0.0F));
    material.transmission.texture =
        textureOf(*transmission, "KHR_materials_transmission", "transmissionTexture");
  }
  if (const tinygltf::Value* volume = extension(source, "KHR_materials_volume")) {
    Transmission& t = material.transmission;
    t.thicknessFactor = std::max(number(*volume, "thicknessFactor", 0.0F), 0.0F);
    t.attenuationColor =
        glm::clamp(color(*volume, "attenuationColor", glm::vec3(1.0F)), 0.0F, 1.0F);
    t.attenuationDistance = std::max(number(*volume, "attenuationDistance", 0.0F), 0.0F);
  }
}

}  // namespace lgh::gltf
