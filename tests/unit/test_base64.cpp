// lgh/base64.hpp: the RFC 4648 test vectors both ways, the strict decoder's refusals (reason and
// offset), and encode -> decode identity over random bytes of every small length and large ones.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <variant>
#include <vector>

#include "lgh/base64.hpp"

namespace lgh {
namespace {

std::vector<std::uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

// RFC 4648 section 10, plus the two characters beyond the letters and digits.
const std::map<std::string, std::string> kVectors{
    {"", ""},
    {"Zg==", "f"},
    {"Zm8=", "fo"},
    {"Zm9v", "foo"},
    {"Zm9vYg==", "foob"},
    {"Zm9vYmE=", "fooba"},
    {"Zm9vYmFy", "foobar"},
    {"+/+/", "\xfb\xff\xbf"},
};

TEST(Base64, Rfc4648Vectors) {
  for (const auto& [encoded, decoded] : kVectors) {
    const auto result = base64::decode(encoded);
    const auto* bytes = std::get_if<std::vector<std::uint8_t>>(&result);
    ASSERT_NE(bytes, nullptr) << encoded;
    EXPECT_EQ(std::string(bytes->begin(), bytes->end()), decoded) << encoded;
    EXPECT_EQ(base64::decodedSize(encoded), decoded.size()) << encoded;
  }
}

TEST(Base64, EncodesRfc4648Vectors) {
  for (const auto& [encoded, decoded] : kVectors) {
    EXPECT_EQ(base64::encode(bytesOf(decoded)), encoded) << encoded;
  }
}

TEST(Base64, RejectsWithReasonAndOffset) {
  using Reason = base64::DecodeError::Reason;
  const std::vector<std::tuple<std::string, Reason, std::size_t>> bad{
      {"Zm9", Reason::Length, 3},           {"Zm9!", Reason::Character, 3},
      {"Z=9v", Reason::Character, 1},       {"Zh==", Reason::PaddingBits, 1},
      {"Zm9=Zm9v", Reason::Character, 3},   {"=m9v", Reason::Character, 0},
      {"Z===", Reason::Character, 1},       {"Zm9v\nZm9v", Reason::Character, 4},
      {"Zm9vYmF=", Reason::PaddingBits, 6},
  };
  for (const auto& [encoded, reason, offset] : bad) {
    const auto result = base64::decode(encoded);
    const auto* error = std::get_if<base64::DecodeError>(&result);
    ASSERT_NE(error, nullptr) << encoded;
    EXPECT_EQ(error->reason, reason) << encoded;
    EXPECT_EQ(error->offset, offset) << encoded;
  }
}

// encode -> decode gives the bytes back; the text is padded to 4 * ceil(n / 3) characters and
// decodedSize predicts n. Every length 0..300 covers each remainder mod 3 many times (0..3
// included); the large lengths cover the three remainders of a multi-megabyte image.
TEST(Base64, RoundTripsRandomBytes) {
  std::mt19937 random(20260601);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::size_t> lengths;
  for (std::size_t n = 0; n <= 300; ++n) lengths.push_back(n);
  for (std::size_t n : {(3U << 20U), (3U << 20U) + 1, (3U << 20U) + 2}) lengths.push_back(n);
  for (const std::size_t length : lengths) {
    std::vector<std::uint8_t> bytes(length);
    for (auto& b : bytes) b = static_cast<std::uint8_t>(byte(random));
    const std::string text = base64::encode(bytes);
    ASSERT_EQ(text.size(), (length + 2) / 3 * 4) << length;
    ASSERT_EQ(base64::decodedSize(text), length) << length;
    const auto result = base64::decode(text);
    const auto* decoded = std::get_if<std::vector<std::uint8_t>>(&result);
    ASSERT_NE(decoded, nullptr) << "length " << length
                                << ": the decoder refused the encoder's text";
    ASSERT_EQ(*decoded, bytes) << length;
  }
}

// Every byte value in every position of a 3-byte group survives the trip.
TEST(Base64, RoundTripsEveryByteValueInEveryPosition) {
  for (std::size_t position = 0; position < 3; ++position) {
    for (int value = 0; value < 256; ++value) {
      std::vector<std::uint8_t> bytes(position + 1, 0x5A);
      bytes[position] = static_cast<std::uint8_t>(value);
      const auto result = base64::decode(base64::encode(bytes));
      const auto* decoded = std::get_if<std::vector<std::uint8_t>>(&result);
      ASSERT_NE(decoded, nullptr) << position << " " << value;
      ASSERT_EQ(*decoded, bytes) << position << " " << value;
    }
  }
}

}  // namespace
}  // namespace lgh
