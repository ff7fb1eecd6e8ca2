// A glTF material's extras.lgh (MaterialConverter::applyExtras): the same material parameters as
// a request's `materials[].parameters` (proto/material-parameters.schema.json), checked by the
// same schema and applied by the same code, with textures naming the asset's glTF textures.
// Errors start with the JSON pointer of the field and name the material:
// "/materials/2/extras/lgh/shininess must be at least 0, got -1 (material 'red')".
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "request/material_parameters.hpp"
#include "scene/gltf/material_converter.hpp"
#include "scene/material_table.hpp"

namespace lgh::gltf {
namespace {

// extras come from the asset's JSON, which tinygltf has parsed without a depth limit of its own.
constexpr int kMaxDepth = 32;

nlohmann::json toJson(const tinygltf::Value& value, int depth, const LoadContext& ctx,
                      const std::string& owner) {
  if (depth > kMaxDepth) {
    invalid(ctx, fmt::format("{}: extras/lgh is nested deeper than {} levels", owner, kMaxDepth));
  }
  switch (value.Type()) {
    case tinygltf::BOOL_TYPE:
      return value.Get<bool>();
    case tinygltf::INT_TYPE:
      return value.GetNumberAsInt();
    case tinygltf::REAL_TYPE:
      return value.GetNumberAsDouble();
    case tinygltf::STRING_TYPE:
      return value.Get<std::string>();
    case tinygltf::ARRAY_TYPE: {
      nlohmann::json array = nlohmann::json::array();
      for (std::size_t i = 0; i < value.ArrayLen(); ++i) {
        array.push_back(toJson(value.Get(static_cast<int>(i)), depth + 1, ctx, owner));
      }
      return array;
    }
    case tinygltf::OBJECT_TYPE: {
      nlohmann::json object = nlohmann::json::object();
      for (const std::string& key : value.Keys()) {
        object[key] = toJson(value.Get(key), depth + 1, ctx, owner);
      }
      return object;
    }
    default:
      return nullptr;
  }
}

}  // namespace

void MaterialConverter::applyExtras(const tinygltf::Material& source, int index,
                                    const std::string& owner, Material& material) {
  if (!source.extras.IsObject() || !source.extras.Has("lgh")) return;
  const std::string where = fmt::format("/materials/{}/extras/lgh", index);
  const nlohmann::json parameters = toJson(source.extras.Get("lgh"), 0, ctx_, owner);
  try {
    const MaterialParameters parsed = parseMaterialParameters(parameters);
    const TextureResolver resolve = [&](const TextureChoice& choice, const std::string& field) {
      if (choice.texture >= static_cast<int>(model_.textures.size())) {
        throw Error(ErrorCode::Invalid,
                    fmt::format("the asset has {} textures, got {}", model_.textures.size(),
                                choice.texture),
                    field);
      }
      return texture(choice.texture, choice.texCoord, {}, owner + " " + field);
    };
    applyMaterialParameters(parsed, resolve, material, "");
  } catch (const Error& error) {
    // Images that fail keep their own error (and status).
    if (error.code() != ErrorCode::Invalid && error.code() != ErrorCode::BadRequest) throw;
    // The field is a pointer inside extras.lgh; the message starts with the asset's own pointer
    // for it, as the loader's other errors do, and names the material.
    const std::string name =
        source.name.empty() ? "" : fmt::format(" (material '{}')", source.name);
    invalid(ctx_, fmt::format("{}{} {}{}", where, error.field(), error.message(), name));
  }
}

}  // namespace lgh::gltf
