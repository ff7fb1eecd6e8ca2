#include "scene/material_table.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "lgh/error.hpp"

namespace lgh {
namespace {

// glTF's sampler values are GL enums; scene data knows no GL, so they are spelled out here.
constexpr int kNearest = 0x2600;
constexpr int kLinear = 0x2601;
constexpr int kNearestMipmapNearest = 0x2700;
constexpr int kLinearMipmapNearest = 0x2701;
constexpr int kNearestMipmapLinear = 0x2702;
constexpr int kLinearMipmapLinear = 0x2703;

int wrapEnum(WrapMode mode) {
  switch (mode) {
    case WrapMode::Repeat:
      return 0x2901;  // GL_REPEAT
    case WrapMode::MirroredRepeat:
      return 0x8370;  // GL_MIRRORED_REPEAT
    case WrapMode::ClampToEdge:
      return 0x812F;  // GL_CLAMP_TO_EDGE
    case WrapMode::ClampToBorder:
      return 0x812D;  // GL_CLAMP_TO_BORDER
  }
  return 0x2901;
}

bool nearestWithin(int minFilter) {
  return minFilter == kNearest || minFilter == kNearestMipmapNearest ||
         minFilter == kNearestMipmapLinear;
}

MipmapMode mipmapMode(int minFilter) {
  if (minFilter == kNearest || minFilter == kLinear) return MipmapMode::None;
  if (minFilter == kNearestMipmapNearest || minFilter == kLinearMipmapNearest) {
    return MipmapMode::Nearest;
  }
  return MipmapMode::Linear;
}

int minFilterEnum(bool nearest, MipmapMode mipmaps) {
  switch (mipmaps) {
    case MipmapMode::None:
      return nearest ? kNearest : kLinear;
    case MipmapMode::Nearest:
      return nearest ? kNearestMipmapNearest : kLinearMipmapNearest;
    case MipmapMode::Linear:
      return nearest ? kNearestMipmapLinear : kLinearMipmapLinear;
  }
  return kLinearMipmapLinear;
}

void applySampling(const SamplingParameters& sampling, Material& material) {
  for (TextureRef* ref : allMaterialTextures(material)) {
    Sampler& s = ref->sampler;
    if (sampling.wrapS) s.wrapS = wrapEnum(*sampling.wrapS);
    if (sampling.wrapT) s.wrapT = wrapEnum(*sampling.wrapT);
    if (sampling.borderColor) {
      const auto& c = *sampling.borderColor;
      s.borderColor = glm::vec4(c[0], c[1], c[2], c[3]);
    }
    if (sampling.filter || sampling.mipmaps) {
      const bool nearest =
          sampling.filter ? *sampling.filter == TextureFilter::Nearest : nearestWithin(s.minFilter);
      const MipmapMode mipmaps = sampling.mipmaps.value_or(mipmapMode(s.minFilter));
      s.minFilter = minFilterEnum(nearest, mipmaps);
      if (sampling.filter) s.magFilter = nearest ? kNearest : kLinear;
    }
    if (sampling.anisotropy) s.anisotropy = *sampling.anisotropy;
  }
  if (sampling.filter) material.bicubic = *sampling.filter == TextureFilter::Bicubic;
}

glm::vec3 vec(const Rgb& rgb) { return {rgb[0], rgb[1], rgb[2]}; }

template <typename T, typename Apply>
void set(const std::optional<T>& value, Apply&& apply) {
  if (value) apply(*value);
}

void applyTextures(const MaterialParameters& p, const TextureResolver& resolve, Material& m,
                   const std::string& pointer) {
  auto texture = [&](const std::optional<TextureChoice>& choice, const char* field,
                     TextureRef& out) {
    if (choice) out = resolve(*choice, pointer + "/" + field + "/texture");
  };
  texture(p.diffuseTexture, "diffuse_texture", m.baseColorTexture);
  texture(p.specularTexture, "specular_texture", m.classic.specularTexture);
  texture(p.shininessTexture, "shininess_texture", m.classic.shininessTexture);
  texture(p.lightMap, "light_map", m.lightMap);
  texture(p.normalTexture, "normal_texture", m.normalTexture);
  texture(p.heightTexture, "height_texture", m.surface.heightTexture);
}

void applySurface(const MaterialParameters& p, SurfaceDetailMaterial& s) {
  set(p.surface, [&](SurfaceDetail v) { s.technique = v; });
  set(p.heightScale, [&](float v) { s.heightScale = v; });
  set(p.parallaxBias, [&](float v) { s.parallaxBias = v; });
  set(p.reliefLinearSteps, [&](int v) { s.reliefLinearSteps = v; });
  set(p.reliefBinarySteps, [&](int v) { s.reliefBinarySteps = v; });
  set(p.reliefSelfShadow, [&](bool v) { s.reliefSelfShadow = v; });
  set(p.reliefSilhouettes, [&](bool v) { s.reliefSilhouettes = v; });
  set(p.tessellationPixels, [&](float v) { s.tessellationPixels = v; });
  set(p.tessellationMaxLevel, [&](int v) { s.tessellationMaxLevel = v; });
}

void applyColors(const MaterialParameters& p, Material& m) {
  set(p.model, [&](MaterialModel v) { m.model = v; });
  set(p.shading, [&](ShadingMode v) { m.classic.shading = v; });
  set(p.diffuse, [&](const Rgb& v) { m.baseColorFactor = glm::vec4(vec(v), m.baseColorFactor.a); });
  set(p.alpha, [&](float v) { m.baseColorFactor.a = v; });
  set(p.ambient, [&](const Rgb& v) { m.classic.ambient = vec(v); });
  set(p.specular, [&](const Rgb& v) { m.classic.specular = vec(v); });
  set(p.emission, [&](const Rgb& v) { m.emissiveFactor = vec(v); });
  set(p.shininess, [&](float v) { m.classic.shininess = v; });
  set(p.sigma, [&](float v) { m.classic.sigma = v; });
  set(p.m, [&](float v) { m.classic.m = v; });
  set(p.f0, [&](const Rgb& v) { m.classic.f0 = vec(v); });
  set(p.metallic, [&](float v) { m.metallicFactor = v; });
  set(p.roughness, [&](float v) { m.roughnessFactor = v; });
  set(p.lightMapStrength, [&](float v) { m.lightMapStrength = v; });
  set(p.alphaMode, [&](AlphaMode v) { m.alphaMode = v; });
  set(p.alphaCutoff, [&](float v) { m.alphaCutoff = v; });
  set(p.doubleSided, [&](bool v) { m.doubleSided = v; });
}

void checkApplies(const MaterialParameters& p, const Material& m, const std::string& pointer) {
  if (m.classic.shading != ShadingMode::Pixel && !isClassicModel(m.model)) {
    throw Error(ErrorCode::Invalid,
                fmt::format("shading '{}' applies to the classic models (phong, blinn-phong, "
                            "oren-nayar, cook-torrance); this material's model is '{}'",
                            enumName(m.classic.shading), enumName(m.model)),
                pointer + (p.shading ? "/shading" : "/model"));
  }
  const SurfaceDetail technique = m.surface.technique;
  if (technique >= SurfaceDetail::Bump && !m.surface.heightTexture.valid()) {
    throw Error(
        ErrorCode::Invalid,
        fmt::format("surface '{}' needs a height map: set height_texture", enumName(technique)),
        pointer + (p.surface ? "/surface" : "/height_texture"));
  }
}

}  // namespace

void applyMaterialParameters(const MaterialParameters& parameters, const TextureResolver& resolve,
                             Material& material, const std::string& pointer) {
  applyColors(parameters, material);
  applyTextures(parameters, resolve, material, pointer);
  applySurface(parameters, material.surface);
  applySampling(parameters.sampling, material);
  checkApplies(parameters, material, pointer);
}

TextureResolver sceneTextureResolver(const Scene& scene) {
  return [&scene](const TextureChoice& choice, const std::string& pointer) {
    if (choice.texture < 0 || static_cast<std::size_t>(choice.texture) >= scene.textures.size()) {
      throw Error(ErrorCode::Invalid,
                  fmt::format("the scene has {} textures (0..{}), got {}", scene.textures.size(),
                              static_cast<int>(scene.textures.size()) - 1, choice.texture),
                  pointer);
    }
    TextureRef ref = scene.textures[static_cast<std::size_t>(choice.texture)];
    if (!ref.valid()) {
      throw Error(ErrorCode::Invalid,
                  fmt::format("texture {} of the scene has no usable image", choice.texture),
                  pointer);
    }
    ref.texCoord = choice.texCoord;
    return ref;
  };
}

MaterialTable::MaterialTable(const Scene& scene, const std::vector<MaterialOverride>& overrides)
    : materials_(scene.materials) {
  const TextureResolver resolve = sceneTextureResolver(scene);
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    const MaterialOverride& entry = overrides[i];
    const std::string base = fmt::format("/materials/{}", i);
    const std::string pointer = base + "/parameters";
    auto apply = [&](Material& material) {
      applyMaterialParameters(entry.parameters, resolve, material, pointer);
    };
    switch (entry.match.kind) {
      case MaterialMatch::Kind::All:
        for (Material& material : materials_) apply(material);
        apply(default_);
        break;
      case MaterialMatch::Kind::Index:
        if (static_cast<std::size_t>(entry.match.index) >= materials_.size()) {
          throw Error(ErrorCode::Invalid,
                      fmt::format("the scene has {} materials, got index {}", materials_.size(),
                                  entry.match.index),
                      base + "/match/index");
        }
        apply(materials_[static_cast<std::size_t>(entry.match.index)]);
        break;
      case MaterialMatch::Kind::Name: {
        bool found = false;
        for (Material& material : materials_) {
          if (material.name != entry.match.name) continue;
          apply(material);
          found = true;
        }
        if (!found) {
          std::string names;
          for (const Material& material : materials_) {
            if (material.name.empty()) continue;
            names += names.empty() ? "" : ", ";
            names += "'" + material.name + "'";
          }
          throw Error(ErrorCode::Invalid,
                      fmt::format("no material named '{}' in this scene (it has {})",
                                  entry.match.name, names.empty() ? "no named materials" : names),
                      base + "/match/name");
        }
        break;
      }
    }
  }
}

const Material& MaterialTable::at(int index) const {
  if (index < 0 || static_cast<std::size_t>(index) >= materials_.size()) return default_;
  return materials_[static_cast<std::size_t>(index)];
}

}  // namespace lgh
