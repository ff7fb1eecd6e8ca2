// Validation of a request against a proto schema (proto/render-request.schema.json and the
// others), with valijson's errors turned into one lgh::Error that names the most specific field
// and says what is wrong with it. validateAgainstProtoSchema is public (lgh/request.hpp).
#pragma once

#include <nlohmann/json.hpp>

namespace lgh {

// Throws lgh::Error: BadRequest for shape errors (type, required, unknown property, enum, const,
// array length), Invalid for range errors (minimum, maximum and their exclusive forms).
void validateRequestSchema(const nlohmann::json& request);

}  // namespace lgh
