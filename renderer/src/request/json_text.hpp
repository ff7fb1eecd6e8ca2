// Parsing request text into JSON with errors that say where: the byte offset of a syntax error,
// and the JSON Pointer of a number too large for a double (nlohmann refuses 1e999 rather than
// parsing it as infinity).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/json_shape.hpp"

namespace lgh {

// The shape every request JSON must keep (render requests, thumbnail batches, multipart request
// parts). The deepest request the schema allows nests 4 levels (/lights/0/position/0); a request
// with the most lights the default limits allow holds about 100,000 values.
inline constexpr JsonShapeLimits kRequestJsonLimits{32, 1'000'000};

// Throws lgh::Error: TooLarge past `shapeLimits` (naming the limit and the byte), BadRequest
// "malformed JSON at byte N: ..." (no field) for a syntax error, Invalid naming the field for a
// number that overflows a double.
nlohmann::json parseJsonText(const std::string& text, const JsonShapeLimits& shapeLimits);

}  // namespace lgh
