// Base64 (RFC 4648 section 4, standard alphabet, with padding), both directions: the renderer
// decodes inline GLB scenes (scene.glb_base64), the daemon encodes images inside JSON answers.
//
// The decoder is strict: padding required, no whitespace, no line breaks, no non-zero bits in the
// padding. Lenient decoders accept garbage that then fails later as a "broken GLB"; refusing it
// here names the real problem.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace lgh::base64 {

// `bytes` as base64 text, padded to a multiple of 4 characters.
std::string encode(std::span<const std::uint8_t> bytes);

struct DecodeError {
  enum class Reason {
    Character,    // not in the alphabet (or '=' before the end)
    Length,       // not a multiple of 4
    PaddingBits,  // the bits beyond the last byte are not zero
  };
  Reason reason = Reason::Character;
  std::size_t offset = 0;  // of the offending character (Character, PaddingBits)
};

// The size `text` decodes to, or nullopt when its length is not a multiple of 4. Lets callers
// check a size limit before allocating.
std::optional<std::size_t> decodedSize(std::string_view text);

// The decoded bytes, or why `text` is not strict base64.
std::variant<std::vector<std::uint8_t>, DecodeError> decode(std::string_view text);

}  // namespace lgh::base64
