// Image I/O: encode/decode round trips, metadata, display conversion, texture decoding, broken
// input and file I/O, against whichever backend this build has (oiio or lean). BackendsAgree
// cross-checks the files of the two backends (pixels, metadata, bytes, texture decodes) when
// LGH_CROSS_CHECK_DIR names a directory shared by an oiio and a lean build (run one build's test,
// then the other's, then the first again).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "lgh/error.hpp"
#include "lgh/image.hpp"
#include "test_support.hpp"

namespace lgh {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

// ---- Synthetic images ----

Image8 patternImage8(int width, int height, int channels, std::uint32_t seed) {
  Image8 image{width, height, channels, {}};
  image.pixels.resize(static_cast<std::size_t>(width) * height * channels);
  std::mt19937 random(seed);
  for (auto& value : image.pixels) value = static_cast<std::uint8_t>(random() & 0xFF);
  return image;
}

// A smooth gradient with HDR values above 1, a negative value and varying alpha.
FloatImage gradientImage(int width, int height) {
  FloatImage image{width, height, {}};
  image.rgba.resize(static_cast<std::size_t>(width) * height * 4);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float* p = image.pixel(x, y);
      p[0] = 4.0F * static_cast<float>(x) / static_cast<float>(width - 1);
      p[1] = static_cast<float>(y) / static_cast<float>(height - 1);
      p[2] = 0.001F + 0.25F * static_cast<float>((x + y) % 7) - (x == 0 && y == 0 ? 1.5F : 0.0F);
      p[3] = static_cast<float>(x + y) / static_cast<float>(width + height - 2);
    }
  }
  return image;
}

// Values that are exactly representable as half: 0.5 steps and a few powers of two.
FloatImage halfExactImage() {
  FloatImage image{3, 2, {0.0F,   0.5F,   1.0F, 1.0F,  2.0F,  0.25F,   -3.5F,   0.0F,
                          1024.F, 0.125F, 6.0F, 0.5F,  7.5F,  0.0625F, 65504.F, 1.0F,
                          0.75F,  1.5F,   3.0F, 0.25F, 1.25F, 8.0F,    16.0F,   0.0F}};
  return image;
}

bool withinHalfRounding(float expected, float actual) {
  // Half has an 11-bit significand: relative error <= 2^-11 ~ 4.9e-4 for normal values; below
  // 2^-14 (subnormals) the absolute step is 2^-24.
  return std::fabs(expected - actual) <= std::max(1e-3F * std::fabs(expected), 6.0e-8F);
}

// ---- A hand-written PNG encoder (stored deflate), independent of both backends ----

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0) {
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320U & (0U - (crc & 1U)));
  }
  return ~crc;
}

void appendBigEndian32(Bytes& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back((value >> shift) & 0xFF);
}

void appendChunk(Bytes& png, const char (&type)[5], const Bytes& body) {
  appendBigEndian32(png, static_cast<std::uint32_t>(body.size()));
  Bytes typed(type, type + 4);
  typed.insert(typed.end(), body.begin(), body.end());
  png.insert(png.end(), typed.begin(), typed.end());
  appendBigEndian32(png, crc32(typed.data(), typed.size()));
}

// zlib stream of uncompressed ("stored") deflate blocks.
Bytes zlibStored(const Bytes& raw) {
  Bytes out = {0x78, 0x01};
  std::size_t offset = 0;
  do {
    const std::size_t length = std::min<std::size_t>(raw.size() - offset, 65535);
    const bool last = offset + length == raw.size();
    out.push_back(last ? 1 : 0);
    out.push_back(length & 0xFF);
    out.push_back(length >> 8);
    out.push_back(~length & 0xFF);
    out.push_back((~length >> 8) & 0xFF);
    out.insert(out.end(), raw.begin() + offset, raw.begin() + offset + length);
    offset += length;
  } while (offset < raw.size());
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t byte : raw) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  appendBigEndian32(out, (b << 16) | a);
  return out;
}

struct HandmadePng {
  std::uint32_t width = 1;
  std::uint32_t height = 1;
  std::uint8_t bitDepth = 8;
  std::uint8_t colorType = 0;  // 0 grey, 2 RGB, 3 palette, 4 grey+alpha, 6 RGBA
  Bytes palette;               // PLTE body
  Bytes transparency;          // tRNS body
  Bytes scanlines;             // each row: filter byte 0, then the row's bytes

  Bytes encode() const {
    Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    Bytes header;
    appendBigEndian32(header, width);
    appendBigEndian32(header, height);
    header.insert(header.end(), {bitDepth, colorType, 0, 0, 0});
    appendChunk(png, "IHDR", header);
    if (!palette.empty()) appendChunk(png, "PLTE", palette);
    if (!transparency.empty()) appendChunk(png, "tRNS", transparency);
    appendChunk(png, "IDAT", zlibStored(scanlines));
    appendChunk(png, "IEND", {});
    return png;
  }
};

// ---- Helpers ----

image_io::Decoded decodeBytes(const Bytes& bytes) { return image_io::decode(bytes, "test"); }

Image8 decodeTexture(const Bytes& bytes, const std::string& what = "test") {
  return image_io::decodeTextureRgba8(bytes.data(), bytes.size(), what);
}

ImageMetadata sorted(ImageMetadata metadata) {
  std::sort(metadata.begin(), metadata.end());
  return metadata;
}

template <typename Function>
ErrorCode errorCodeOf(Function&& function) {
  try {
    function();
  } catch (const Error& error) {
    return error.code();
  }
  ADD_FAILURE() << "no lgh::Error thrown";
  return ErrorCode::Internal;
}

std::uint8_t toDisplay1(float value, ToneMap toneMap, float exposure = 1.0F) {
  const FloatImage image{1, 1, {value, value, value, 1.0F}};
  return toDisplay8(image, toneMap, exposure, false).pixels[0];
}

double referenceSrgb(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

Bytes pngOf(const Image8& image, const ImageMetadata& metadata = {}) {
  return image_io::encodePng(image, metadata);
}

// ---- PNG ----

class PngRoundTrip : public ::testing::TestWithParam<int> {};

TEST_P(PngRoundTrip, DecodesExactPixels) {
  const int channels = GetParam();
  const Image8 image = patternImage8(37, 23, channels, 1000 + channels);
  const auto decoded = decodeBytes(pngOf(image));
  EXPECT_EQ(decoded.width, 37);
  EXPECT_EQ(decoded.height, 23);
  EXPECT_EQ(decoded.channels, channels);
  EXPECT_FALSE(decoded.isFloat);
  EXPECT_EQ(decoded.pixels8, image.pixels);
}

INSTANTIATE_TEST_SUITE_P(Channels, PngRoundTrip, ::testing::Values(1, 2, 3, 4),
                         [](const auto& info) { return "Channels" + std::to_string(info.param); });

TEST(ImageIoPng, KeepsStraightAlphaUnchanged) {
  // A premultiplying reader or writer would zero the colour of transparent pixels.
  const Image8 image{2, 1, 4, {200, 100, 50, 0, 10, 20, 30, 128}};
  EXPECT_EQ(decodeBytes(pngOf(image)).pixels8, image.pixels);
}

TEST(ImageIoPng, MetadataRoundTrips) {
  const ImageMetadata metadata = {
      {"Software", "lghd"},
      {"Title", "gradient"},
      {"Description", "a test image"},
      {"Author", "image_io test"},
      {"Comment", "line one\nline two"},
      {"lgh:request", R"({"output":{"width":64,"toneMap":"aces"},"name":"h\u00e9"})"},
      {"lgh:long", std::string(3000, 'x')}};
  const auto decoded = decodeBytes(pngOf(patternImage8(4, 4, 3, 7), metadata));
  EXPECT_EQ(sorted(decoded.metadata), sorted(metadata));
}

TEST(ImageIoPng, EveryCompressionLevelKeepsThePixels) {
  // A smooth image compresses well, so the levels' sizes differ visibly.
  Image8 image{96, 64, 3, {}};
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) image.pixels.push_back(static_cast<std::uint8_t>(x + y * c));
    }
  }
  std::vector<std::size_t> sizes;
  for (int level = 0; level <= 9; ++level) {
    const Bytes png = image_io::encodePng(image, {}, level);
    EXPECT_EQ(decodeBytes(png).pixels8, image.pixels) << "level " << level;
    sizes.push_back(png.size());
  }
  EXPECT_GT(sizes[0], image.pixels.size()) << "level 0 stores the rows uncompressed";
  EXPECT_LT(sizes[9], sizes[1]);
  EXPECT_LT(sizes[1], sizes[0]);
}

TEST(ImageIoPng, CompressionLevelOutsideZlibsRangeIsInvalid) {
  for (const int level : {-1, 10}) {
    try {
      image_io::encodePng(patternImage8(4, 4, 3, 1), {}, level);
      ADD_FAILURE() << "level " << level << " was accepted";
    } catch (const Error& error) {
      EXPECT_EQ(error.code(), ErrorCode::Invalid);
      EXPECT_NE(std::string(error.what()).find(std::to_string(level)), std::string::npos)
          << error.what();
    }
  }
}

// ---- EXR ----

TEST(ImageIoExr, FloatRoundTripIsExact) {
  FloatImage image = gradientImage(19, 11);
  image.pixel(3, 4)[1] = 1.0e-30F;
  image.pixel(5, 6)[2] = 3.0e30F;
  const auto decoded = decodeBytes(image_io::encodeExr(image, false));
  EXPECT_EQ(decoded.width, 19);
  EXPECT_EQ(decoded.height, 11);
  EXPECT_EQ(decoded.channels, 4);
  ASSERT_TRUE(decoded.isFloat);
  EXPECT_EQ(decoded.pixelsFloat, image.rgba);
}

TEST(ImageIoExr, HalfRoundTripWithinHalfRounding) {
  const FloatImage image = gradientImage(19, 11);
  const auto decoded = decodeBytes(image_io::encodeExr(image, true));
  ASSERT_TRUE(decoded.isFloat);
  ASSERT_EQ(decoded.channels, 4);
  ASSERT_EQ(decoded.pixelsFloat.size(), image.rgba.size());
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    EXPECT_TRUE(withinHalfRounding(image.rgba[i], decoded.pixelsFloat[i]))
        << "value " << i << ": " << image.rgba[i] << " came back as " << decoded.pixelsFloat[i];
  }
  const FloatImage exact = halfExactImage();
  EXPECT_EQ(decodeBytes(image_io::encodeExr(exact, true)).pixelsFloat, exact.rgba);
}

TEST(ImageIoExr, MetadataRoundTrips) {
  const ImageMetadata metadata = {{"Software", "lghd"},
                                  {"Title", "gradient"},
                                  {"comments", "linear scene-referred"},
                                  {"owner", "test"},
                                  {"capDate", "2024:01:02 03:04:05"},
                                  {"lgh:request", R"({"output":{"format":"exr-half"}})"}};
  const auto decoded = decodeBytes(image_io::encodeExr(gradientImage(4, 4), true, metadata));
  EXPECT_EQ(sorted(decoded.metadata), sorted(metadata));
}

TEST(ImageIoExr, StampsCaptureDateWhenNoneGiven) {
  // OpenImageIO always writes capDate; the lean backend does the same so their files agree.
  const auto decoded =
      decodeBytes(image_io::encodeExr(gradientImage(2, 2), false, {{"Software", "lghd"}}));
  ASSERT_EQ(decoded.metadata.size(), 2U);
  const auto date = std::find_if(decoded.metadata.begin(), decoded.metadata.end(),
                                 [](const auto& entry) { return entry.first == "capDate"; });
  ASSERT_NE(date, decoded.metadata.end());
  EXPECT_EQ(date->second.size(), 19U) << date->second;  // YYYY:MM:DD hh:mm:ss
}

TEST(ImageIoMetadata, RejectsKeysOneBackendCannotStore) {
  const Image8 png = patternImage8(2, 2, 3, 1);
  const FloatImage exr = gradientImage(2, 2);
  auto pngWith = [&](const ImageMetadata& m) { return [&png, m] { image_io::encodePng(png, m); }; };
  auto exrWith = [&](const ImageMetadata& m) {
    return [&exr, m] { image_io::encodeExr(exr, true, m); };
  };
  EXPECT_EQ(errorCodeOf(pngWith({{"DateTime", "now"}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(pngWith({{"oiio:ColorSpace", "sRGB"}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(pngWith({{"", "empty key"}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(pngWith({{" padded", "x"}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(pngWith({{std::string(80, 'k'), "x"}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(pngWith({{"a", "1"}, {"a", "2"}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(pngWith({{"a", std::string("nul\0byte", 8)}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(exrWith({{"compression", "zip"}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(exrWith({{"Description", "renamed by OIIO"}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(exrWith({{"png:foo", "x"}})), ErrorCode::Invalid);
  // OpenImageIO matches names without regard to case.
  EXPECT_EQ(errorCodeOf(pngWith({{"DESCRIPTION", "x"}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(pngWith({{"Name", "x"}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(exrWith({{"Comments", "x"}})), ErrorCode::Invalid);
  EXPECT_EQ(errorCodeOf(exrWith({{"copyright", "x"}})), ErrorCode::Invalid);
}

// ---- Display conversion ----

TEST(ImageIoDisplay, KnownValues) {
  EXPECT_EQ(toDisplay1(0.0F, ToneMap::None), 0);
  EXPECT_EQ(toDisplay1(0.0F, ToneMap::Aces), 0);
  EXPECT_EQ(toDisplay1(1.0F, ToneMap::None), 255);
  EXPECT_EQ(toDisplay1(0.5F, ToneMap::None), 188);
  EXPECT_EQ(toDisplay1(1.0F, ToneMap::Reinhard), 188);         // 1 / (1 + 1) = 0.5
  EXPECT_EQ(toDisplay1(0.25F, ToneMap::None, 2.0F), 188);      // exposure first
  EXPECT_EQ(toDisplay1(0.0031308F * 0.5F, ToneMap::None), 5);  // linear segment: 12.92 x
  // Narkowicz ACES of 1.0: 2.54 / 3.16 = 0.8038 -> sRGB 0.9084 -> 231.6.
  EXPECT_EQ(toDisplay1(1.0F, ToneMap::Aces), 232);
  EXPECT_EQ(toDisplay1(1000.0F, ToneMap::Aces), 255);
}

TEST(ImageIoDisplay, ClampsOutOfRangeValues) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (ToneMap mode : {ToneMap::None, ToneMap::Reinhard, ToneMap::Aces}) {
    EXPECT_EQ(toDisplay1(-2.0F, mode), 0);
    EXPECT_EQ(toDisplay1(nan, mode), 0);
    EXPECT_EQ(toDisplay1(inf, mode), 255);
    EXPECT_EQ(toDisplay1(5.0F, mode, 1.0e30F), 255);
  }
}

TEST(ImageIoDisplay, MatchesTheExactOetfRoundedToNearest) {
  std::vector<float> values;
  for (int i = 0; i <= 200000; ++i) values.push_back(static_cast<float>(i) / 200000.0F);
  // The float neighbours of every rounding boundary, where a table or a float pow would slip.
  for (int k = 0; k < 255; ++k) {
    const double encoded = (k + 0.5) / 255.0;
    const double boundary =
        encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
    const float near = static_cast<float>(boundary);
    values.insert(values.end(), {std::nextafter(near, 0.0F), near, std::nextafter(near, 2.0F)});
  }
  FloatImage image{static_cast<int>(values.size()), 1, {}};
  for (float v : values) image.rgba.insert(image.rgba.end(), {v, v, v, 1.0F});
  const Image8 display = toDisplay8(image, ToneMap::None, 1.0F, false);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double expected = std::floor(255.0 * referenceSrgb(values[i]) + 0.5);
    ASSERT_EQ(display.pixels[i * 3], expected) << "linear " << values[i];
  }
}

TEST(ImageIoDisplay, AlphaIsKeptLinearOnlyWhenAsked) {
  const FloatImage image{2, 1, {0.5F, 0.5F, 0.5F, 0.5F, 1.0F, 0.0F, 0.0F, 2.0F}};
  const Image8 opaque = toDisplay8(image, ToneMap::None, 1.0F, false);
  EXPECT_EQ(opaque.channels, 3);
  EXPECT_EQ(opaque.pixels, (Bytes{188, 188, 188, 255, 0, 0}));
  const Image8 withAlpha = toDisplay8(image, ToneMap::None, 1.0F, true);
  EXPECT_EQ(withAlpha.channels, 4);
  EXPECT_EQ(withAlpha.pixels, (Bytes{188, 188, 188, 128, 255, 0, 0, 255}));
}

TEST(ImageIoEncode, FollowsOutputSettings) {
  const FloatImage image = gradientImage(8, 5);
  OutputSettings output;
  output.format = ImageFormat::Png;
  output.transparentBackground = false;
  EXPECT_EQ(decodeBytes(encodeImage(image, output)).channels, 3);
  output.transparentBackground = true;
  const auto rgba = decodeBytes(encodeImage(image, output));
  EXPECT_EQ(rgba.pixels8, toDisplay8(image, output.toneMap, output.exposure, true).pixels);
  output.pngCompression = 0;
  EXPECT_EQ(decodeBytes(encodeImage(image, output)).pixels8, rgba.pixels8);
  EXPECT_GT(encodeImage(image, output).size(), rgba.pixels8.size()) << "level 0: stored rows";
  output.format = ImageFormat::ExrFloat;
  EXPECT_EQ(decodeBytes(encodeImage(image, output)).pixelsFloat, image.rgba);
  output.format = ImageFormat::ExrHalf;
  EXPECT_TRUE(decodeBytes(encodeImage(image, output)).isFloat);
  EXPECT_STREQ(mimeType(ImageFormat::Png), "image/png");
  EXPECT_STREQ(mimeType(ImageFormat::ExrHalf), "image/x-exr");
  EXPECT_STREQ(fileExtension(ImageFormat::Png), ".png");
  EXPECT_STREQ(fileExtension(ImageFormat::ExrFloat), ".exr");
}

// ---- Textures ----

TEST(ImageIoTexture, ExpandsGreyAndPaletteToRgba) {
  HandmadePng grey{3, 1, 8, 0, {}, {}, {0, 0, 128, 255}};
  EXPECT_EQ(decodeTexture(grey.encode()).pixels,
            (Bytes{0, 0, 0, 255, 128, 128, 128, 255, 255, 255, 255, 255}));
  HandmadePng greyAlpha{2, 1, 8, 4, {}, {}, {0, 10, 20, 30, 40}};
  EXPECT_EQ(decodeTexture(greyAlpha.encode()).pixels, (Bytes{10, 10, 10, 20, 30, 30, 30, 40}));
  HandmadePng palette{2, 1, 8, 3, {1, 2, 3, 4, 5, 6}, {0}, {0, 0, 1}};
  EXPECT_EQ(decodeTexture(palette.encode()).pixels, (Bytes{1, 2, 3, 0, 4, 5, 6, 255}));
  const Image8 rgb = patternImage8(5, 3, 3, 42);
  const Image8 rgba = decodeTexture(pngOf(rgb));
  ASSERT_EQ(rgba.channels, 4);
  for (std::size_t i = 0; i < 15; ++i) {
    EXPECT_EQ(rgba.pixels[i * 4 + 0], rgb.pixels[i * 3 + 0]);
    EXPECT_EQ(rgba.pixels[i * 4 + 2], rgb.pixels[i * 3 + 2]);
    EXPECT_EQ(rgba.pixels[i * 4 + 3], 255);
  }
}

TEST(ImageIoTexture, Reduces16BitWithRounding) {
  // 16-bit RGB, one pixel per row: v / 257 rounded to nearest.
  HandmadePng deep{1,
                   2,
                   16,
                   2,
                   {},
                   {},
                   {0, 0x12, 0x34, 0x80, 0x80, 0xFF, 0xFF,  //
                    0, 0x00, 0xFF, 0x00, 0x80, 0x00, 0x00}};
  EXPECT_EQ(decodeTexture(deep.encode()).pixels, (Bytes{18, 128, 255, 255, 1, 0, 0, 255}));
  const auto decoded = decodeBytes(deep.encode());
  EXPECT_FALSE(decoded.isFloat);
  EXPECT_EQ(decoded.pixels8, (Bytes{18, 128, 255, 1, 0, 0}));
}

TEST(ImageIoTexture, DecodesRealPngAndJpegTextures) {
  const fs::path jpeg = test::assimpGltfDir() / "ClearCoat-glTF" / "PlasticWrap_normals.jpg";
  const fs::path png = test::assimpGltfDir() / "BoxTextured-glTF" / "CesiumLogoFlat.png";
  if (!fs::exists(jpeg) || !fs::exists(png)) GTEST_SKIP() << "assimp-testmodels not installed";
  const Image8 normals = decodeTexture(image_io::readFile(jpeg), jpeg.string());
  ASSERT_EQ(normals.width, 1024);
  ASSERT_EQ(normals.height, 1024);
  ASSERT_EQ(normals.channels, 4);
  // A tangent-space normal map: mostly (128, 128, 255), opaque.
  std::array<double, 4> mean{};
  for (std::size_t i = 0; i < normals.pixels.size(); ++i) mean[i % 4] += normals.pixels[i];
  for (double& m : mean) m /= 1024.0 * 1024.0;
  EXPECT_NEAR(mean[0], 128, 20);
  EXPECT_NEAR(mean[1], 128, 20);
  EXPECT_GT(mean[2], 200);
  EXPECT_EQ(mean[3], 255);
  const Image8 logo = decodeTexture(image_io::readFile(png), png.string());  // palette PNG
  EXPECT_EQ(logo.width, 211);
  EXPECT_EQ(logo.pixels.size(), 211U * 211U * 4U);
}

TEST(ImageIoTexture, RejectsOversizedImagesBeforeDecoding) {
  // Headers only claim the size; the one row of data would not fill it.
  HandmadePng wide{20000, 1, 8, 0, {}, {}, {0, 0}};
  EXPECT_EQ(errorCodeOf([&] { decodeTexture(wide.encode()); }), ErrorCode::TooLarge);
  EXPECT_EQ(errorCodeOf([&] { decodeBytes(wide.encode()); }), ErrorCode::TooLarge);
  HandmadePng tall{1, 16385, 8, 0, {}, {}, {0, 0}};
  EXPECT_EQ(errorCodeOf([&] { decodeTexture(tall.encode()); }), ErrorCode::TooLarge);
  // A decompression bomb within the limits: 16 M pixels from 100 bytes cannot be deflate data.
  HandmadePng bomb{4096, 4096, 8, 0, {}, {}, Bytes(100, 0)};
  EXPECT_EQ(errorCodeOf([&] { decodeTexture(bomb.encode()); }), ErrorCode::Invalid);
  // 16384 is still allowed.
  HandmadePng limit{16384, 1, 8, 0, {}, {}, Bytes(16385, 7)};
  limit.scanlines[0] = 0;
  EXPECT_EQ(decodeTexture(limit.encode()).width, 16384);
}

// ---- Hand-written OpenEXR headers ----

void appendLittleEndian32(Bytes& out, std::uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back((value >> shift) & 0xFF);
}

void appendExrAttribute(Bytes& exr, const std::string& name, const std::string& type,
                        std::uint32_t claimedSize, const Bytes& value) {
  exr.insert(exr.end(), name.begin(), name.end());
  exr.push_back(0);
  exr.insert(exr.end(), type.begin(), type.end());
  exr.push_back(0);
  appendLittleEndian32(exr, claimedSize);
  exr.insert(exr.end(), value.begin(), value.end());
}

Bytes exrWithDataWindow(std::int32_t xMax, std::int32_t yMax) {
  Bytes exr = {0x76, 0x2F, 0x31, 0x01, 2, 0, 0, 0};
  Bytes box;
  for (std::int32_t v : {0, 0, xMax, yMax}) {
    appendLittleEndian32(box, static_cast<std::uint32_t>(v));
  }
  appendExrAttribute(exr, "dataWindow", "box2i", 16, box);
  return exr;
}

TEST(ImageIoExr, HeaderClaimsAreCheckedBeforeAllocating) {
  // OpenEXR would allocate (and zero) 2 GiB for this string attribute, or an offset table for
  // every claimed scanline, before noticing the file is a few bytes long.
  Bytes hugeString = exrWithDataWindow(0, 0);
  appendExrAttribute(hugeString, "comments", "string", 0x7FFFFFFF, {'x'});
  EXPECT_EQ(errorCodeOf([&] { decodeBytes(hugeString); }), ErrorCode::Invalid);
  Bytes hugeImage = exrWithDataWindow(99999, 0);
  hugeImage.push_back(0);
  EXPECT_EQ(errorCodeOf([&] { decodeBytes(hugeImage); }), ErrorCode::TooLarge);
  Bytes tinyTiles = exrWithDataWindow(16383, 16383);
  appendExrAttribute(tinyTiles, "tiles", "tiledesc", 9, {1, 0, 0, 0, 1, 0, 0, 0, 0});
  tinyTiles.push_back(0);
  EXPECT_EQ(errorCodeOf([&] { decodeBytes(tinyTiles); }), ErrorCode::Invalid);
}

// ---- Broken input ----

// Every broken input must end in lgh::Error(Invalid) naming the source, never a crash.
void expectInvalid(const Bytes& bytes, const std::string& label) {
  for (bool texture : {false, true}) {
    try {
      if (texture) {
        decodeTexture(bytes, "broken.bin");
      } else {
        image_io::decode(bytes, "broken.bin");
      }
      ADD_FAILURE() << label << ": decoded without error";
    } catch (const Error& error) {
      EXPECT_EQ(error.code(), ErrorCode::Invalid) << label << ": " << error.what();
      EXPECT_EQ(error.field(), "broken.bin") << label;
      EXPECT_FALSE(error.message().empty()) << label;
      const std::string what = error.what();
      EXPECT_TRUE(
          std::all_of(what.begin(), what.end(), [](char c) { return c >= 0x20 && c <= 0x7E; }))
          << label << ": message is not printable ASCII: " << what;
    }
  }
}

TEST(ImageIoBroken, GarbageBytesAreInvalid) {
  std::mt19937 random(1234);
  Bytes garbage(4096);
  for (auto& b : garbage) b = random() & 0xFF;
  expectInvalid({}, "empty");
  expectInvalid(garbage, "random bytes");
  const std::vector<Bytes> magics = {
      {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'}, {0x76, 0x2F, 0x31, 0x01}, {0xFF, 0xD8, 0xFF}};
  for (const Bytes& magic : magics) {
    Bytes withMagic = garbage;
    std::copy(magic.begin(), magic.end(), withMagic.begin());
    expectInvalid(withMagic, "magic number + random bytes");
    expectInvalid(magic, "magic number alone");
  }
}

TEST(ImageIoBroken, TruncatedFilesAreInvalid) {
  const Bytes png = pngOf(patternImage8(32, 32, 4, 5), {{"Software", "lghd"}});
  const Bytes exr = image_io::encodeExr(gradientImage(32, 32), true, {{"Software", "lghd"}});
  for (const Bytes* file : {&png, &exr}) {
    for (std::size_t length :
         {std::size_t{10}, std::size_t{40}, file->size() / 2, file->size() - 13}) {
      expectInvalid(Bytes(file->begin(), file->begin() + length),
                    "truncated to " + std::to_string(length));
    }
  }
}

TEST(ImageIoBroken, CorruptedFilesNeverCrash) {
  const Bytes png = pngOf(patternImage8(16, 16, 4, 9), {{"Software", "lghd"}});
  const Bytes exr = image_io::encodeExr(gradientImage(16, 16), false, {{"Software", "lghd"}});
  std::mt19937 random(99);
  int errors = 0;
  for (const Bytes* file : {&png, &exr}) {
    for (int round = 0; round < 100; ++round) {
      Bytes corrupted = *file;
      for (int flips = 0; flips < 4; ++flips) {
        corrupted[random() % corrupted.size()] ^= static_cast<std::uint8_t>(1 + random() % 255);
      }
      try {
        image_io::decode(corrupted, "corrupted");
        decodeTexture(corrupted, "corrupted");
      } catch (const Error&) {
        ++errors;  // a decode that succeeds on damaged pixel data is fine too
      }
    }
  }
  EXPECT_GT(errors, 0);
}

// ---- Files ----

TEST(ImageIoFiles, WriteThenReadRoundTrips) {
  const fs::path dir = test::outputDir() / "image_io_files";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Bytes bytes = patternImage8(100, 100, 3, 77).pixels;
  image_io::writeFile(dir / "data.bin", bytes);
  EXPECT_EQ(image_io::readFile(dir / "data.bin"), bytes);
  image_io::writeFile(dir / "data.bin", Bytes{1, 2, 3});  // replaces
  EXPECT_EQ(image_io::readFile(dir / "data.bin"), (Bytes{1, 2, 3}));
  image_io::writeFile(dir / "empty.bin", {});
  EXPECT_TRUE(image_io::readFile(dir / "empty.bin").empty());
  // No temporary files left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

TEST(ImageIoFiles, MissingFileIsNotFoundNamingThePath) {
  const fs::path missing = test::outputDir() / "no_such_dir" / "missing.png";
  try {
    image_io::readFile(missing);
    FAIL() << "read a missing file";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::NotFound);
    EXPECT_EQ(error.field(), missing.string());
    EXPECT_NE(std::string(error.what()).find("missing.png"), std::string::npos) << error.what();
  }
  EXPECT_EQ(errorCodeOf([&] { image_io::writeFile(missing, {1}); }), ErrorCode::NotFound);
  EXPECT_EQ(errorCodeOf([&] { image_io::readFile(test::outputDir()); }), ErrorCode::Invalid);
}

// ---- Cross-backend check ----

const char* otherBackend() {
  return std::string(image_io::backendName()) == "oiio" ? "lean" : "oiio";
}

ImageMetadata crossCheckMetadata(const std::string& writer) {
  return {{"Software", "lghd image_io test"},
          {"Title", "gradient"},
          {"capDate", "2024:01:02 03:04:05"},
          {"lgh:writer", writer}};
}

// The fixed images every backend writes: the PNG from toDisplay8 of the gradient (RGBA), the EXR
// the gradient itself.
FloatImage crossCheckImage() { return gradientImage(64, 48); }
Image8 crossCheckImage8() { return toDisplay8(crossCheckImage(), ToneMap::Aces, 1.0F, true); }

// Writes this backend's files: the PNG and EXR (half), and its decodes of two real textures
// (re-encoded as PNG, losslessly) so the other backend can compare texture decoding too.
void writeCrossCheckFiles(const fs::path& dir) {
  const std::string self = image_io::backendName();
  const fs::path stem = dir / ("image_io_" + self);
  image_io::writeFile(fs::path(stem) += ".png",
                      pngOf(crossCheckImage8(), crossCheckMetadata(self)));
  image_io::writeFile(fs::path(stem) += ".exr",
                      image_io::encodeExr(crossCheckImage(), true, crossCheckMetadata(self)));
  const fs::path jpeg = test::assimpGltfDir() / "ClearCoat-glTF" / "PlasticWrap_normals.jpg";
  const fs::path palette = test::assimpGltfDir() / "BoxTextured-glTF" / "CesiumLogoFlat.png";
  if (fs::exists(jpeg) && fs::exists(palette)) {
    image_io::writeFile(fs::path(stem) += "_jpeg_texture.png",
                        pngOf(decodeTexture(image_io::readFile(jpeg))));
    image_io::writeFile(fs::path(stem) += "_palette_texture.png",
                        pngOf(decodeTexture(image_io::readFile(palette))));
  }
}

// Compares the two backends' decodes of the same texture, written by writeCrossCheckFiles.
void compareTextureDecodes(const fs::path& dir, const std::string& suffix, const char* label,
                           int maxDifference) {
  const fs::path other = dir / (std::string("image_io_") + otherBackend() + suffix);
  const fs::path mine = dir / (std::string("image_io_") + image_io::backendName() + suffix);
  if (!fs::exists(other) || !fs::exists(mine)) return;
  const auto theirs = decodeBytes(image_io::readFile(other));
  const auto ours = decodeBytes(image_io::readFile(mine));
  ASSERT_EQ(theirs.pixels8.size(), ours.pixels8.size()) << label;
  int largest = 0;
  double total = 0;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < ours.pixels8.size(); ++i) {
    const int difference = std::abs(ours.pixels8[i] - theirs.pixels8[i]);
    largest = std::max(largest, difference);
    total += difference;
    differing += difference != 0;
  }
  std::cout << "[ cross    ] " << label << ": " << differing << " of " << ours.pixels8.size()
            << " values differ, largest difference " << largest << ", mean "
            << total / static_cast<double>(ours.pixels8.size()) << "\n";
  EXPECT_LE(largest, maxDifference) << label;
}

// LGH_REQUIRE_CROSS_CHECK=1 (scripts/run-tests) turns "nothing to compare" into a failure.
bool crossCheckRequired() {
  const char* value = std::getenv("LGH_REQUIRE_CROSS_CHECK");
  return value != nullptr && std::string(value) == "1";
}

// Writes this backend's files for the cross-check (into LGH_CROSS_CHECK_DIR when set).
TEST(ImageIo, WritesCrossCheckFiles) {
  writeCrossCheckFiles(test::outputDir());
  const char* dirVariable = std::getenv("LGH_CROSS_CHECK_DIR");
  if (dirVariable == nullptr || *dirVariable == '\0') return;
  fs::create_directories(dirVariable);
  writeCrossCheckFiles(dirVariable);
  EXPECT_TRUE(fs::exists(fs::path(dirVariable) /
                         (std::string("image_io_") + image_io::backendName() + ".png")));
}

// Compares the other backend's files (written by its WritesCrossCheckFiles) with this one's.
TEST(ImageIo, BackendsAgree) {
  const char* dirVariable = std::getenv("LGH_CROSS_CHECK_DIR");
  if (dirVariable == nullptr || *dirVariable == '\0') {
    if (crossCheckRequired())
      FAIL() << "LGH_REQUIRE_CROSS_CHECK=1 but LGH_CROSS_CHECK_DIR is unset";
    GTEST_SKIP() << "set LGH_CROSS_CHECK_DIR to a directory shared by an oiio and a lean build";
  }
  const fs::path dir = dirVariable;
  fs::create_directories(dir);
  writeCrossCheckFiles(dir);
  const fs::path stem = dir / (std::string("image_io_") + otherBackend());
  const fs::path png = fs::path(stem) += ".png";
  const fs::path exr = fs::path(stem) += ".exr";
  if (!fs::exists(png) || !fs::exists(exr)) {
    if (crossCheckRequired()) {
      FAIL() << "LGH_REQUIRE_CROSS_CHECK=1 but there are no files from the " << otherBackend()
             << " backend in " << dir << ": nothing to compare";
    }
    GTEST_SKIP() << "no files from the " << otherBackend() << " backend in " << dir
                 << " yet: run its test_image_io with the same LGH_CROSS_CHECK_DIR";
  }
  const ImageMetadata expectedMetadata = sorted(crossCheckMetadata(otherBackend()));

  const auto theirPng = decodeBytes(image_io::readFile(png));
  EXPECT_EQ(theirPng.channels, 4);
  EXPECT_EQ(theirPng.pixels8, crossCheckImage8().pixels) << "PNG pixels differ";
  EXPECT_EQ(sorted(theirPng.metadata), expectedMetadata);

  const auto theirExr = decodeBytes(image_io::readFile(exr));
  const auto ourExr = decodeBytes(image_io::encodeExr(crossCheckImage(), true));
  ASSERT_EQ(theirExr.pixelsFloat.size(), ourExr.pixelsFloat.size());
  const FloatImage source = crossCheckImage();
  std::size_t identical = 0;
  for (std::size_t i = 0; i < source.rgba.size(); ++i) {
    EXPECT_TRUE(withinHalfRounding(source.rgba[i], theirExr.pixelsFloat[i])) << "EXR value " << i;
    identical += theirExr.pixelsFloat[i] == ourExr.pixelsFloat[i];
  }
  std::cout << "[ cross    ] EXR half: " << identical << " of " << source.rgba.size()
            << " values identical to this backend's encoding\n";
  EXPECT_EQ(sorted(theirExr.metadata), expectedMetadata);

  // Beyond pixels: encoding the same image and metadata here gives the other backend's bytes.
  EXPECT_TRUE(image_io::readFile(png) ==
              pngOf(crossCheckImage8(), crossCheckMetadata(otherBackend())))
      << "the PNG files of the two backends differ in their bytes";
  EXPECT_TRUE(image_io::readFile(exr) ==
              image_io::encodeExr(crossCheckImage(), true, crossCheckMetadata(otherBackend())))
      << "the EXR files of the two backends differ in their bytes";

  compareTextureDecodes(dir, "_palette_texture.png", "palette PNG texture", 0);
  // Both backends decode JPEG with libjpeg-turbo, with its default (islow) IDCT: identical.
  compareTextureDecodes(dir, "_jpeg_texture.png", "JPEG texture", 0);
}

}  // namespace
}  // namespace lgh
