// Material models and texturing techniques of the lecture (docs/MATERIALS.md): the names a request
// (`materials`, proto/material-parameters.schema.json) and a glTF material's `extras.lgh` use, and
// the typed form of one set of material parameters. Every field is optional: a parameter set
// changes only what it names.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lgh/enum_names.hpp"

namespace lgh {

// How the lighting passes shade a material: written to the G-buffer as a small integer and
// switched on by evaluateBrdfLobes() in glsl/include/brdf.glsl (numbers kept in step with
// glsl/include/material_models.glsl).
enum class MaterialModel : std::uint8_t {
  MetallicRoughness = 0,  // glTF PBR (GGX), with the KHR_materials_* layers
  Unlit = 1,              // KHR_materials_unlit (and lines/points without normals)
  Phong = 2,              // the lecture's Phong: (R.V)^shininess
  BlinnPhong = 3,         // the lecture's Blinn-Phong: (N.H)^shininess
  OrenNayar = 4,          // rough diffuse, roughness sigma
  CookTorrance = 5,       // Beckmann distribution, V-cavity geometric term, Schlick Fresnel
};
template <>
struct EnumNames<MaterialModel> {
  static constexpr std::array<EnumName<MaterialModel>, 6> names{{
      {"metallic-roughness", MaterialModel::MetallicRoughness},
      {"unlit", MaterialModel::Unlit},
      {"phong", MaterialModel::Phong},
      {"blinn-phong", MaterialModel::BlinnPhong},
      {"oren-nayar", MaterialModel::OrenNayar},
      {"cook-torrance", MaterialModel::CookTorrance},
  }};
};

// The lecture's models other than glTF's: they take ambient/specular colours and the shading
// modes below.
constexpr bool isClassicModel(MaterialModel model) {
  return model != MaterialModel::MetallicRoughness && model != MaterialModel::Unlit;
}

// Where the classic models evaluate the analytic lights: once per primitive, per vertex
// (interpolated), or per pixel.
enum class ShadingMode : std::uint8_t { Pixel = 0, Gouraud = 1, Flat = 2 };
template <>
struct EnumNames<ShadingMode> {
  static constexpr std::array<EnumName<ShadingMode>, 3> names{{
      {"pixel", ShadingMode::Pixel},
      {"gouraud", ShadingMode::Gouraud},
      {"flat", ShadingMode::Flat},
  }};
};

// Surface detail: what the normal map and the height map do.
enum class SurfaceDetail : std::uint8_t {
  None = 0,          // neither: the texture alone
  Normal = 1,        // the normal map where there is one (glTF's behaviour)
  Bump = 2,          // normals from the height map by central differences
  Parallax = 3,      // texture coordinates offset by the height (scale, bias)
  Relief = 4,        // height-field ray march (linear + binary search), self-shadowing
  Displacement = 5,  // tessellated geometry moved along the vertex normal
};
template <>
struct EnumNames<SurfaceDetail> {
  static constexpr std::array<EnumName<SurfaceDetail>, 6> names{{
      {"none", SurfaceDetail::None},
      {"normal", SurfaceDetail::Normal},
      {"bump", SurfaceDetail::Bump},
      {"parallax", SurfaceDetail::Parallax},
      {"relief", SurfaceDetail::Relief},
      {"displacement", SurfaceDetail::Displacement},
  }};
};

enum class AlphaMode { Opaque, Mask, Blend };
template <>
struct EnumNames<AlphaMode> {
  static constexpr std::array<EnumName<AlphaMode>, 3> names{{
      {"opaque", AlphaMode::Opaque},
      {"mask", AlphaMode::Mask},
      {"blend", AlphaMode::Blend},
  }};
};

enum class WrapMode { Repeat, MirroredRepeat, ClampToEdge, ClampToBorder };
template <>
struct EnumNames<WrapMode> {
  static constexpr std::array<EnumName<WrapMode>, 4> names{{
      {"repeat", WrapMode::Repeat},
      {"mirrored-repeat", WrapMode::MirroredRepeat},
      {"clamp-to-edge", WrapMode::ClampToEdge},
      {"clamp-to-border", WrapMode::ClampToBorder},
  }};
};

// Filtering within a mip level; bicubic runs in the shader (Catmull-Rom from bilinear taps).
enum class TextureFilter { Nearest, Linear, Bicubic };
template <>
struct EnumNames<TextureFilter> {
  static constexpr std::array<EnumName<TextureFilter>, 3> names{{
      {"nearest", TextureFilter::Nearest},
      {"linear", TextureFilter::Linear},
      {"bicubic", TextureFilter::Bicubic},
  }};
};

// Filtering between mip levels: none (level 0 only), the nearest level, or linear (trilinear).
enum class MipmapMode { None, Nearest, Linear };
template <>
struct EnumNames<MipmapMode> {
  static constexpr std::array<EnumName<MipmapMode>, 3> names{{
      {"none", MipmapMode::None},
      {"nearest", MipmapMode::Nearest},
      {"linear", MipmapMode::Linear},
  }};
};

// How every texture of a material is sampled; unset fields keep the glTF sampler's values.
struct SamplingParameters {
  std::optional<WrapMode> wrapS;
  std::optional<WrapMode> wrapT;
  std::optional<std::array<float, 4>> borderColor;  // linear RGBA, for clamp-to-border
  std::optional<TextureFilter> filter;
  std::optional<MipmapMode> mipmaps;
  std::optional<float> anisotropy;  // 1..16, capped at the device's maximum
};

// A texture of the scene (the glTF asset's textures array; the demo's own list) on a UV set.
struct TextureChoice {
  int texture = 0;
  int texCoord = 0;
};

using Rgb = std::array<float, 3>;

// One set of material parameters: a request's `materials[i].parameters` or a glTF material's
// `extras.lgh`. Only what is set changes the material.
struct MaterialParameters {
  std::optional<MaterialModel> model;
  std::optional<ShadingMode> shading;
  // Colours and factors (linear RGB). diffuse is glTF's base colour.
  std::optional<Rgb> diffuse;
  std::optional<float> alpha;
  std::optional<Rgb> ambient;   // classic models; unset: the diffuse colour
  std::optional<Rgb> specular;  // Phong, Blinn-Phong
  std::optional<Rgb> emission;
  std::optional<float> shininess;  // Phong, Blinn-Phong exponent
  std::optional<float> sigma;      // Oren-Nayar roughness, radians
  std::optional<float> m;          // Cook-Torrance roughness (RMS microfacet slope)
  std::optional<Rgb> f0;           // Cook-Torrance Fresnel reflectance at normal incidence
  std::optional<float> metallic;   // metallic-roughness
  std::optional<float> roughness;  // metallic-roughness
  // Multi-texturing.
  std::optional<TextureChoice> diffuseTexture;
  std::optional<TextureChoice> specularTexture;   // specular map (colour and intensity)
  std::optional<TextureChoice> shininessTexture;  // gloss map: shininess x R
  std::optional<TextureChoice> lightMap;          // precomputed illumination, multiplied in
  std::optional<float> lightMapStrength;
  std::optional<TextureChoice> normalTexture;
  std::optional<TextureChoice> heightTexture;
  // Alpha.
  std::optional<AlphaMode> alphaMode;
  std::optional<float> alphaCutoff;
  std::optional<bool> doubleSided;
  // Surface detail.
  std::optional<SurfaceDetail> surface;
  std::optional<float> heightScale;
  std::optional<float> parallaxBias;
  std::optional<int> reliefLinearSteps;
  std::optional<int> reliefBinarySteps;
  std::optional<bool> reliefSelfShadow;
  std::optional<bool> reliefSilhouettes;
  std::optional<float> tessellationPixels;  // displacement: target edge length on screen
  std::optional<int> tessellationMaxLevel;
  SamplingParameters sampling;
};

// Which materials a request's parameter set applies to.
struct MaterialMatch {
  enum class Kind { Name, Index, All };
  Kind kind = Kind::All;
  std::string name;
  int index = 0;
};

// One entry of the request's `materials`: applied, in order, over the scene's materials for this
// frame only (the cached scene keeps its own).
struct MaterialOverride {
  MaterialMatch match;
  MaterialParameters parameters;
};

}  // namespace lgh
