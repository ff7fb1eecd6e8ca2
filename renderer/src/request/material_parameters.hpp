// JSON -> MaterialParameters (proto/material-parameters.schema.json), for the request's
// `materials` and for glTF materials' extras.lgh alike. The JSON must have passed the schema.
#pragma once

#include <nlohmann/json.hpp>

#include "lgh/material_settings.hpp"

namespace lgh {

MaterialParameters readMaterialParameters(const nlohmann::json& object);

// One entry of the request's `materials` (render-request.schema.json#/$defs/material_override).
MaterialOverride readMaterialOverride(const nlohmann::json& object);

// Validates `object` against material-parameters.schema.json, then reads it. Throws lgh::Error
// naming the field by its JSON pointer inside `object`.
MaterialParameters parseMaterialParameters(const nlohmann::json& object);

}  // namespace lgh
