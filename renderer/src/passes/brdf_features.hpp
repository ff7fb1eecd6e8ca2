// The material models and layers a frame's G-buffer can hold, from the frame's materials (the
// MaterialTable: the scene's with the request's overrides) and the draw items that use them: what
// the LGH lighting kernels are compiled for (LGH_BRDF_MODELS and LGH_BRDF_LAYERS of
// glsl/include/brdf.glsl), so that a kernel evaluating thousands of lights per pixel carries only
// the BRDF code the frame's surfaces need (docs/LIGHTING.md, "Specialised BRDF").
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "lgh/material_settings.hpp"
#include "scene/gpu_scene.hpp"
#include "scene/material_table.hpp"

namespace lgh {

// MATERIAL_LAYER_* bits of glsl/include/material_models.glsl.
inline constexpr std::uint32_t kLayerClearcoat = 1U;
inline constexpr std::uint32_t kLayerSheen = 2U;
inline constexpr std::uint32_t kLayerSpecular = 4U;
inline constexpr std::uint32_t kLayerTransmission = 8U;

// The layer bits a metallic-roughness material writes to the G-buffer.
std::uint32_t materialLayerBits(const Material& material);

struct BrdfFeatures {
  static constexpr std::uint32_t kAllModels = (1U << EnumNames<MaterialModel>::names.size()) - 1U;
  static constexpr std::uint32_t kAllLayers =
      kLayerClearcoat | kLayerSheen | kLayerSpecular | kLayerTransmission;

  std::uint32_t models = kAllModels;  // bit 1 << MaterialModel per model
  std::uint32_t layers = kAllLayers;  // the layer bits of the metallic-roughness surfaces

  static BrdfFeatures none() { return {0U, 0U}; }
  // A surface of `model`; `layerBits` count for metallic-roughness only (the classic models use
  // the G-buffer's layer byte for flags of their own).
  void add(MaterialModel model, std::uint32_t layerBits);
  bool has(MaterialModel model) const { return (models & modelBit(model)) != 0U; }
  bool all() const { return models == kAllModels && layers == kAllLayers; }
  // Whether a surface of the frame writes the G-buffer's layers target (include/gbuffer.glsl):
  // metallic-roughness with a layer, or a classic model (their parameters live there).
  bool usesLayersTarget() const;
  // "#define LGH_BRDF_MODELS ..." and "#define LGH_BRDF_LAYERS ..."; none where every model and
  // layer is present, so that the generic kernel is the shader as written.
  std::string defines() const;
  // For the frame report: "all", or "metallic-roughness,phong layers:clearcoat".
  std::string describe() const;
  bool operator==(const BrdfFeatures&) const = default;

  static constexpr std::uint32_t modelBit(MaterialModel model) {
    return 1U << static_cast<std::uint32_t>(model);
  }
};

// What the G-buffer of a frame that draws `items` with `materials` can hold: each item's model as
// the G-buffer pass shades it (effectiveModel: lines and points without normals are unlit) and,
// for metallic-roughness, its material's layers.
BrdfFeatures brdfFeatures(const MaterialTable& materials,
                          std::span<const GpuScene::DrawItem> items);

// Whether any of `items` writes emission into the G-buffer's emissive target: an emissive
// factor, an unlit surface (its colour is its emission) or a light map.
bool surfacesEmit(const MaterialTable& materials, std::span<const GpuScene::DrawItem> items);

}  // namespace lgh
