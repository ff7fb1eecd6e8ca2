// Standard base64 (RFC 4648 section 4) with padding, for images inside JSON answers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lghd {

std::string base64Encode(const std::vector<std::uint8_t>& bytes);

}  // namespace lghd
