// Finds the schema nodes that apply to one value of a document, to phrase validation errors
// ("must be one of png, exr", "must be at most 8192"). Best effort: it follows "$ref" (local,
// as in a bundle), "properties", "additionalProperties", "items", "allOf" and "if"/"then"/"else"
// where the condition is a simple type test or a discriminator ({"properties": {"type":
// {"const": ...}}}); anything else it does not evaluate includes both branches.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace lgh {

// The value at `tokens` in `document`, or nullptr when there is none.
const nlohmann::json* valueAt(const nlohmann::json& document,
                              const std::vector<std::string>& tokens);

// The schema nodes of `bundle` that apply to the value at `tokens` of `document`. The value need
// not exist (a missing required property still gets its parent's "properties" entry).
std::vector<const nlohmann::json*> schemaNodesAt(const nlohmann::json& bundle,
                                                 const nlohmann::json& document,
                                                 const std::vector<std::string>& tokens);

}  // namespace lgh
