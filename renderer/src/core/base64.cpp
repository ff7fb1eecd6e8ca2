#include "lgh/base64.hpp"

#include <array>

namespace lgh::base64 {
namespace {

constexpr std::string_view kAlphabet =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
constexpr int kInvalid = -1;

constexpr std::array<int, 256> makeDecodeTable() {
  std::array<int, 256> table{};
  table.fill(kInvalid);
  for (std::size_t i = 0; i < kAlphabet.size(); ++i) {
    table[static_cast<unsigned char>(kAlphabet[i])] = static_cast<int>(i);
  }
  return table;
}

constexpr std::array<int, 256> kDecodeTable = makeDecodeTable();

int sextet(char c) { return kDecodeTable[static_cast<unsigned char>(c)]; }

std::size_t paddingLength(std::string_view text) {
  if (text.ends_with("==")) return 2;
  if (text.ends_with("=")) return 1;
  return 0;
}

// The first character before the padding that is not in the alphabet.
std::optional<std::size_t> firstInvalidCharacter(std::string_view data) {
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (sextet(data[i]) == kInvalid) return i;
  }
  return std::nullopt;
}

// The character of the 6 bits of `group` that start `shift` bits above its lowest bit.
char character(std::uint32_t group, int shift) { return kAlphabet[(group >> shift) & 63U]; }

}  // namespace

std::string encode(std::span<const std::uint8_t> bytes) {
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t group = (std::uint32_t{bytes[i]} << 16U) |
                                (std::uint32_t{bytes[i + 1]} << 8U) | std::uint32_t{bytes[i + 2]};
    text += character(group, 18);
    text += character(group, 12);
    text += character(group, 6);
    text += character(group, 0);
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    const std::uint32_t group =
        (std::uint32_t{bytes[i]} << 16U) | (rest == 2 ? std::uint32_t{bytes[i + 1]} << 8U : 0U);
    text += character(group, 18);
    text += character(group, 12);
    text += rest == 2 ? character(group, 6) : '=';
    text += '=';
  }
  return text;
}

std::optional<std::size_t> decodedSize(std::string_view text) {
  if (text.size() % 4 != 0) return std::nullopt;
  return text.size() / 4 * 3 - paddingLength(text);
}

std::variant<std::vector<std::uint8_t>, DecodeError> decode(std::string_view text) {
  using Reason = DecodeError::Reason;
  const std::string_view data = text.substr(0, text.size() - paddingLength(text));
  // Characters first: a line break is better reported as such than as a length problem.
  if (const auto invalid = firstInvalidCharacter(data)) {
    return DecodeError{Reason::Character, *invalid};
  }
  const std::optional<std::size_t> size = decodedSize(text);
  if (!size) return DecodeError{Reason::Length, text.size()};

  std::vector<std::uint8_t> bytes;
  bytes.reserve(*size);
  std::uint32_t bits = 0;
  int bitCount = 0;
  for (const char c : data) {
    bits = (bits << 6) | static_cast<std::uint32_t>(sextet(c));
    bitCount += 6;
    if (bitCount >= 8) {
      bitCount -= 8;
      bytes.push_back(static_cast<std::uint8_t>((bits >> bitCount) & 0xFFU));
    }
  }
  // The bits left over from the last group must be zero (RFC 4648 section 3.5): otherwise
  // different texts would decode to the same bytes.
  if ((bits & ((1U << bitCount) - 1U)) != 0) {
    return DecodeError{Reason::PaddingBits, data.size() - 1};
  }
  return bytes;
}

}  // namespace lgh::base64
