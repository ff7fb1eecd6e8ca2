// Parsing request text into JSON with errors that say where: the byte offset of a syntax error,
// and the JSON Pointer of a number too large for a double (nlohmann refuses 1e999 rather than
// parsing it as infinity).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace lgh {

// Throws lgh::Error: BadRequest "malformed JSON at byte N: ..." (no field) for a syntax error,
// Invalid naming the field for a number that overflows a double.
nlohmann::json parseJsonText(const std::string& text);

}  // namespace lgh
