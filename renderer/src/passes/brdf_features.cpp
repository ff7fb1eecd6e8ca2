#include "passes/brdf_features.hpp"

#include <array>
#include <utility>

#include <fmt/format.h>

#include "passes/material_binding.hpp"

namespace lgh {
namespace {

constexpr std::array<std::pair<std::uint32_t, const char*>, 4> kLayerNames{{
    {kLayerClearcoat, "clearcoat"},
    {kLayerSheen, "sheen"},
    {kLayerSpecular, "specular"},
    {kLayerTransmission, "transmission"},
}};

std::string modelNames(std::uint32_t models) {
  std::string names;
  for (const auto& entry : EnumNames<MaterialModel>::names) {
    if ((models & BrdfFeatures::modelBit(entry.value)) == 0U) continue;
    if (!names.empty()) names += ',';
    names += entry.name;
  }
  return names.empty() ? "none" : names;
}

std::string layerNames(std::uint32_t layers) {
  std::string names;
  for (const auto& [bit, name] : kLayerNames) {
    if ((layers & bit) == 0U) continue;
    if (!names.empty()) names += ',';
    names += name;
  }
  return names.empty() ? "none" : names;
}

}  // namespace

std::uint32_t materialLayerBits(const Material& m) {
  std::uint32_t layers = 0;
  if (m.clearcoat.factor > 0.0F) layers |= kLayerClearcoat;
  if (m.sheen.colorFactor != glm::vec3(0.0F)) layers |= kLayerSheen;
  const bool specular = m.specular.factor != 1.0F || m.specular.colorFactor != glm::vec3(1.0F) ||
                        m.specular.ior != 1.5F || m.specular.texture.valid() ||
                        m.specular.colorTexture.valid();
  if (specular) layers |= kLayerSpecular;
  if (m.transmission.factor > 0.0F) layers |= kLayerTransmission;
  return layers;
}

void BrdfFeatures::add(MaterialModel model, std::uint32_t layerBits) {
  models |= modelBit(model);
  if (model == MaterialModel::MetallicRoughness) layers |= layerBits;
}

bool BrdfFeatures::usesLayersTarget() const {
  if (layers != 0U) return true;
  for (const auto& entry : EnumNames<MaterialModel>::names) {
    if (isClassicModel(entry.value) && has(entry.value)) return true;
  }
  return false;
}

std::string BrdfFeatures::defines() const {
  if (all()) return {};
  return fmt::format("#define LGH_BRDF_MODELS {}\n#define LGH_BRDF_LAYERS {}\n", models, layers);
}

std::string BrdfFeatures::describe() const {
  if (all()) return "all";
  return modelNames(models) + " layers:" + layerNames(layers);
}

BrdfFeatures brdfFeatures(const MaterialTable& materials,
                          std::span<const GpuScene::DrawItem> items) {
  BrdfFeatures features = BrdfFeatures::none();
  for (const GpuScene::DrawItem& item : items) {
    const Material& material = materials.at(item.material);
    features.add(effectiveModel(material, item.unlit), materialLayerBits(material));
  }
  return features;
}

bool surfacesEmit(const MaterialTable& materials, std::span<const GpuScene::DrawItem> items) {
  for (const GpuScene::DrawItem& item : items) {
    const Material& material = materials.at(item.material);
    if (material.emissiveFactor != glm::vec3(0.0F) || material.lightMap.valid() ||
        effectiveModel(material, item.unlit) == MaterialModel::Unlit) {
      return true;
    }
  }
  return false;
}

}  // namespace lgh
