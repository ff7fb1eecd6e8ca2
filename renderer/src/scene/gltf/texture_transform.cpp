#include "scene/gltf/texture_transform.hpp"

#include <cmath>

#include <fmt/format.h>

namespace lgh::gltf {
namespace {

// Element `i` of a JSON number array, or `fallback` when it is missing or not finite.
float arrayNumber(const tinygltf::Value& array, int i, float fallback, bool& repaired) {
  if (!array.IsArray() || i >= static_cast<int>(array.ArrayLen())) return fallback;
  const tinygltf::Value& element = array.Get(i);
  if (!element.IsNumber()) {
    repaired = true;
    return fallback;
  }
  const double value = element.GetNumberAsDouble();
  if (!std::isfinite(value)) {
    repaired = true;
    return fallback;
  }
  return static_cast<float>(value);
}

}  // namespace

UvTransform readTextureTransform(const tinygltf::ExtensionMap& extensions, const std::string& owner,
                                 LoadContext& ctx, int& texCoord) {
  UvTransform transform;
  const auto it = extensions.find("KHR_texture_transform");
  if (it == extensions.end() || !it->second.IsObject()) return transform;
  const tinygltf::Value& value = it->second;
  bool repaired = false;
  if (value.Has("offset")) {
    const tinygltf::Value& offset = value.Get("offset");
    transform.offset = {arrayNumber(offset, 0, 0.0F, repaired),
                        arrayNumber(offset, 1, 0.0F, repaired)};
  }
  if (value.Has("scale")) {
    const tinygltf::Value& scale = value.Get("scale");
    transform.scale = {arrayNumber(scale, 0, 1.0F, repaired),
                       arrayNumber(scale, 1, 1.0F, repaired)};
  }
  if (value.Has("rotation") && value.Get("rotation").IsNumber()) {
    const double rotation = value.Get("rotation").GetNumberAsDouble();
    if (std::isfinite(rotation)) {
      transform.rotation = static_cast<float>(rotation);
    } else {
      repaired = true;
    }
  }
  if (value.Has("texCoord") && value.Get("texCoord").IsInt()) {
    texCoord = value.Get("texCoord").GetNumberAsInt();
  }
  if (repaired) {
    ctx.warnings.push_back(fmt::format(
        "{}: KHR_texture_transform has non-numeric or non-finite values; defaults used", owner));
  }
  return transform;
}

}  // namespace lgh::gltf
