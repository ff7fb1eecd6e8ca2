// Response headers built from request data (the warnings of a render name assets, nodes and
// images of the client's scene, without bound) must stay small: proxies answer 502 when a
// response's headers pass their buffer, 4 to 8 KB by default (nginx proxy_buffer_size, Envoy,
// AWS ALB). Headers that carry a list as JSON keep as many whole entries as fit and end with an
// entry that says how many were left out; the JSON body (Accept: application/json) always holds
// them all.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace lghd {

// Caps for the headers of a render answer; together well below the smallest proxy buffer.
inline constexpr std::size_t kWarningsHeaderBytes = 2048;
inline constexpr std::size_t kPathsHeaderBytes = 1024;

// `items` as a compact ASCII JSON array of at most `maxBytes` (at least 200): whole items while
// they fit, then "... N more (the JSON body has them all)".
std::string cappedJsonArray(const std::vector<std::string>& items, std::size_t maxBytes);

// `entries` as a compact ASCII JSON object of at most `maxBytes` (at least 200): whole entries
// while they fit, then "truncated": "N more ...".
std::string cappedJsonObject(const std::map<std::string, std::string>& entries,
                             std::size_t maxBytes);

}  // namespace lghd
