// JSON Pointers (RFC 6901) as the request errors name fields: "/lights/2/position/1".
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace lgh {

// One reference token, escaped ("a/b" -> "a~1b", "a~b" -> "a~0b").
std::string escapePointerToken(std::string_view token);
// "/" + escaped tokens joined by "/"; "" for no tokens.
std::string joinPointer(const std::vector<std::string>& tokens);

}  // namespace lgh
