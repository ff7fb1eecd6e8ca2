// Schema pre-check. tinygltf ignores members of the wrong JSON type (a "scene": "hello" or a
// "primitives" object just vanish), which turns a broken asset into a silently different one.
// This checks the members we (or tinygltf) consume against the glTF 2.0 schema's types first.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace lgh::gltf {

// Throws lgh::Error(Invalid, "invalid glTF: <JSON pointer> <problem>", displayName) for the first
// member of the wrong type, missing required member or array of the wrong length, e.g.
// "invalid glTF: /meshes/0/primitives must be an array".
void checkSchema(const nlohmann::json& document, const std::string& displayName);

}  // namespace lgh::gltf
