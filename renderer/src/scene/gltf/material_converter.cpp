#include "scene/gltf/material_converter.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

#include <fmt/format.h>

#include "scene/gltf/image_decoding.hpp"
#include "scene/gltf/side_files.hpp"
#include "scene/gltf/texture_transform.hpp"

namespace lgh::gltf {

float finiteOr(double value, float fallback) {
  return std::isfinite(value) ? static_cast<float>(value) : fallback;
}

namespace {

bool knownFilter(int filter, bool minification) {
  switch (filter) {
    case TINYGLTF_TEXTURE_FILTER_NEAREST:
    case TINYGLTF_TEXTURE_FILTER_LINEAR:
      return true;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR:
      return minification;
    default:
      return false;
  }
}

bool knownWrap(int wrap) {
  return wrap == TINYGLTF_TEXTURE_WRAP_REPEAT || wrap == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ||
         wrap == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
}

}  // namespace

MaterialConverter::MaterialConverter(const tinygltf::Model& model, LoadContext& ctx, Scene& scene)
    : model_(model), ctx_(ctx), scene_(scene) {}

Material MaterialConverter::convert(int index) {
  const tinygltf::Material& source = model_.materials[static_cast<std::size_t>(index)];
  const std::string owner = fmt::format("/materials/{}", index);
  Material material;
  material.name = source.name;
  const auto& pbr = source.pbrMetallicRoughness;
  for (int c = 0; c < 4 && c < static_cast<int>(pbr.baseColorFactor.size()); ++c) {
    material.baseColorFactor[c] = std::clamp(finiteOr(pbr.baseColorFactor[c], 1.0F), 0.0F, 1.0F);
  }
  material.metallicFactor = std::clamp(finiteOr(pbr.metallicFactor, 1.0F), 0.0F, 1.0F);
  material.roughnessFactor = std::clamp(finiteOr(pbr.roughnessFactor, 1.0F), 0.0F, 1.0F);
  material.emissiveFactor = emissive(source);
  material.normalScale = finiteOr(source.normalTexture.scale, 1.0F);
  material.occlusionStrength =
      std::clamp(finiteOr(source.occlusionTexture.strength, 1.0F), 0.0F, 1.0F);
  material.alphaMode = alphaMode(source.alphaMode, owner);
  material.alphaCutoff = std::max(finiteOr(source.alphaCutoff, 0.5F), 0.0F);
  material.doubleSided = source.doubleSided;
  material.baseColorTexture =
      texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
              pbr.baseColorTexture.extensions, owner + "/pbrMetallicRoughness/baseColorTexture");
  material.metallicRoughnessTexture =
      texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
              pbr.metallicRoughnessTexture.extensions,
              owner + "/pbrMetallicRoughness/metallicRoughnessTexture");
  material.normalTexture = texture(source.normalTexture.index, source.normalTexture.texCoord,
                                   source.normalTexture.extensions, owner + "/normalTexture");
  material.occlusionTexture =
      texture(source.occlusionTexture.index, source.occlusionTexture.texCoord,
              source.occlusionTexture.extensions, owner + "/occlusionTexture");
  material.emissiveTexture = texture(source.emissiveTexture.index, source.emissiveTexture.texCoord,
                                     source.emissiveTexture.extensions, owner + "/emissiveTexture");
  readExtensions(source, owner, material);
  applyExtras(source, index, owner, material);
  return material;
}

TextureRef MaterialConverter::textureFromValue(const tinygltf::Value& info,
                                               const std::string& owner) {
  if (!info.IsObject() || !info.Has("index") || !info.Get("index").IsInt()) return {};
  const int index = info.Get("index").GetNumberAsInt();
  const int texCoord = info.Has("texCoord") && info.Get("texCoord").IsInt()
                           ? info.Get("texCoord").GetNumberAsInt()
                           : 0;
  tinygltf::ExtensionMap extensions;
  if (info.Has("extensions") && info.Get("extensions").IsObject()) {
    const tinygltf::Value& map = info.Get("extensions");
    for (const std::string& key : map.Keys()) extensions.emplace(key, map.Get(key));
  }
  return texture(index, texCoord, extensions, owner);
}

void MaterialConverter::warnAboutUnusedFailures() {
  for (const auto& [index, error] : ctx_.imageErrors) {
    if (imageRemap_.count(index) == 0) {
      ctx_.warnings.push_back(fmt::format("unused image skipped: {}", error.message()));
    }
  }
}

std::vector<TextureRef> MaterialConverter::allTextures() {
  std::vector<TextureRef> textures;
  textures.reserve(model_.textures.size());
  for (std::size_t i = 0; i < model_.textures.size(); ++i) {
    try {
      textures.push_back(texture(static_cast<int>(i), 0, {},
                                 label("texture", static_cast<int>(i), model_.textures[i].name)));
    } catch (const Error&) {
      textures.emplace_back();  // a material using it has failed the load already
    }
  }
  return textures;
}

glm::vec3 MaterialConverter::emissive(const tinygltf::Material& source) const {
  glm::vec3 factor(0.0F);
  for (int c = 0; c < 3 && c < static_cast<int>(source.emissiveFactor.size()); ++c) {
    factor[c] = std::max(finiteOr(source.emissiveFactor[c], 0.0F), 0.0F);
  }
  const auto it = source.extensions.find("KHR_materials_emissive_strength");
  if (it != source.extensions.end() && it->second.Has("emissiveStrength")) {
    const tinygltf::Value& strength = it->second.Get("emissiveStrength");
    if (strength.IsNumber()) {
      factor *= std::max(finiteOr(strength.GetNumberAsDouble(), 1.0F), 0.0F);
    }
  }
  return factor;
}

AlphaMode MaterialConverter::alphaMode(const std::string& mode, const std::string& owner) const {
  if (mode == "OPAQUE") return AlphaMode::Opaque;
  if (mode == "MASK") return AlphaMode::Mask;
  if (mode == "BLEND") return AlphaMode::Blend;
  ctx_.warnings.push_back(fmt::format("{}: unknown alphaMode '{}', OPAQUE used", owner, mode));
  return AlphaMode::Opaque;
}

int MaterialConverter::textureImage(const tinygltf::Texture& texture) const {
  const auto dds = texture.extensions.find("MSFT_texture_dds");
  if (dds != texture.extensions.end() && dds->second.Has("source") &&
      dds->second.Get("source").IsInt()) {
    return dds->second.Get("source").GetNumberAsInt();
  }
  const auto webp = texture.extensions.find("EXT_texture_webp");
  if (webp != texture.extensions.end() && webp->second.Has("source") &&
      webp->second.Get("source").IsInt()) {
    return webp->second.Get("source").GetNumberAsInt();
  }
  return texture.source;
}

TextureRef MaterialConverter::texture(int textureIndex, int texCoord,
                                      const tinygltf::ExtensionMap& extensions,
                                      const std::string& owner) {
  if (textureIndex < 0) return {};
  if (static_cast<std::size_t>(textureIndex) >= model_.textures.size()) {
    invalid(ctx_,
            fmt::format("{}/index names texture {}, which does not exist", owner, textureIndex));
  }
  const tinygltf::Texture& source = model_.textures[static_cast<std::size_t>(textureIndex)];
  const int image = textureImage(source);
  if (image < 0) {
    ctx_.warnings.push_back(
        fmt::format("{}: /textures/{} has no image in a supported format; "
                    "ignored",
                    owner, textureIndex));
    return {};
  }
  if (static_cast<std::size_t>(image) >= model_.images.size()) {
    invalid(ctx_, fmt::format("{}: /textures/{} names image {}, which does not exist", owner,
                              textureIndex, image));
  }
  TextureRef ref;
  ref.image = sceneImage(image);
  ref.transform = readTextureTransform(extensions, owner, ctx_, texCoord);
  ref.texCoord = texCoord;
  if (texCoord != 0 && texCoord != 1) {
    ctx_.warnings.push_back(
        fmt::format("{}: TEXCOORD_{} is not supported; TEXCOORD_0 used", owner, texCoord));
    ref.texCoord = 0;
  }
  ref.sampler = sampler(source.sampler, owner);
  return ref;
}

Sampler MaterialConverter::sampler(int index, const std::string& owner) const {
  Sampler result;
  if (index < 0) return result;
  if (static_cast<std::size_t>(index) >= model_.samplers.size()) {
    invalid(ctx_, fmt::format("{}: sampler {} does not exist", owner, index));
  }
  const tinygltf::Sampler& source = model_.samplers[static_cast<std::size_t>(index)];
  // -1 is tinygltf's "not given": keep our defaults silently; other unknown values warn.
  if (knownFilter(source.magFilter, false)) result.magFilter = source.magFilter;
  if (knownFilter(source.minFilter, true)) result.minFilter = source.minFilter;
  if (knownWrap(source.wrapS)) result.wrapS = source.wrapS;
  if (knownWrap(source.wrapT)) result.wrapT = source.wrapT;
  const bool filtersOk = (source.magFilter == -1 || knownFilter(source.magFilter, false)) &&
                         (source.minFilter == -1 || knownFilter(source.minFilter, true));
  if (!filtersOk || !knownWrap(source.wrapS) || !knownWrap(source.wrapT)) {
    ctx_.warnOnce(
        fmt::format("/samplers/{} has invalid filter or wrap values; defaults used", index));
  }
  return result;
}

int MaterialConverter::sceneImage(int index) {
  if (const auto it = imageRemap_.find(index); it != imageRemap_.end()) return it->second;
  if (const auto failed = ctx_.imageErrors.find(index); failed != ctx_.imageErrors.end()) {
    throw failed->second;
  }
  const auto decoded = ctx_.images.find(index);
  if (decoded == ctx_.images.end()) throw missingImageError(index);
  scene_.images.push_back(std::move(decoded->second));
  ctx_.images.erase(decoded);
  const int sceneIndex = static_cast<int>(scene_.images.size()) - 1;
  if (const auto blocks = ctx_.blockImages.find(index); blocks != ctx_.blockImages.end()) {
    scene_.compressedImages.emplace(sceneIndex, std::move(blocks->second));
    ctx_.blockImages.erase(blocks);
  }
  imageRemap_.emplace(index, sceneIndex);
  return sceneIndex;
}

Error MaterialConverter::missingImageError(int index) const {
  const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
  const std::string decodedUri = percentDecodedUri(image.uri);
  if (const auto it = ctx_.fileErrors.find(uriKey(decodedUri)); it != ctx_.fileErrors.end()) {
    return it->second;
  }
  return Error(ErrorCode::Invalid, fmt::format("{} could not be loaded", imageLabel(image, index)),
               ctx_.displayName);
}

}  // namespace lgh::gltf
