// Images in memory and their encoding. One interface, two backends chosen at configure time
// (LGH_IMAGE_IO=oiio|lean); nothing outside renderer/src/image knows which one is built.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "lgh/request.hpp"

namespace lgh {

// Linear-light float RGBA, rows top to bottom.
struct FloatImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // width * height * 4

  float* pixel(int x, int y) { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
  const float* pixel(int x, int y) const { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
};

// 8-bit image, `channels` 1..4, rows top to bottom.
struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 4;
  std::vector<std::uint8_t> pixels;
};

// An 8-bit image in memory someone else owns (a mapped read-back buffer): `channels` 1..4, rows
// top to bottom, tightly packed.
struct Image8View {
  int width = 0;
  int height = 0;
  int channels = 4;
  const std::uint8_t* pixels = nullptr;
};

// Linear RGBA in memory someone else owns: half floats (IEEE binary16) or floats, rows top to
// bottom, tightly packed.
struct LinearRgbaView {
  int width = 0;
  int height = 0;
  bool halfFloat = false;
  const void* pixels = nullptr;
};

class TaskPool;

// Text attributes written into files: PNG tEXt chunks, EXR string attributes.
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

namespace image_io {

// Name of the backend compiled in: "oiio" or "lean".
const char* backendName();

// PNG, 8 bits per channel, channels as given (3 = RGB, 4 = RGBA); zlib level 0..9 (0 stores,
// 1 is fastest, 9 smallest). With a pool, a large image is filtered and deflated on its idle
// workers too (docs/IMAGES.md, "PNG encoder"). The same encoder in both backends.
std::vector<std::uint8_t> encodePng(const Image8View& image, const ImageMetadata& metadata = {},
                                    int compressionLevel = kDefaultPngCompression,
                                    TaskPool* pool = nullptr);
std::vector<std::uint8_t> encodePng(const Image8& image, const ImageMetadata& metadata = {},
                                    int compressionLevel = kDefaultPngCompression,
                                    TaskPool* pool = nullptr);
// OpenEXR, RGBA, linear: a half-float file from half pixels (stored as they are) or from floats
// (rounded to nearest even), a float file from floats.
std::vector<std::uint8_t> encodeExr(const LinearRgbaView& image, bool halfFloat,
                                    const ImageMetadata& metadata = {});
std::vector<std::uint8_t> encodeExr(const FloatImage& image, bool halfFloat,
                                    const ImageMetadata& metadata = {});

// Decoded file contents, for tests and for reading back what was written.
struct Decoded {
  int width = 0;
  int height = 0;
  int channels = 0;
  bool isFloat = false;
  std::vector<std::uint8_t> pixels8;  // when !isFloat
  std::vector<float> pixelsFloat;     // when isFloat
  ImageMetadata metadata;
};
// Decodes PNG or EXR (and JPEG; with OIIO every format it reads) from memory.
// Throws lgh::Error(Invalid) with `what` naming the source on a broken file.
Decoded decode(const std::vector<std::uint8_t>& bytes, const std::string& what);

// Texture images for glTF: PNG and JPEG in both backends, always decoded to 8-bit RGBA.
Image8 decodeTextureRgba8(const std::uint8_t* data, std::size_t size, const std::string& what);

void writeFile(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes);
std::vector<std::uint8_t> readFile(const std::filesystem::path& path);

}  // namespace image_io

// Tone mapping (ToneMap) + exposure + sRGB encoding of a linear image to 8 bits.
Image8 toDisplay8(const FloatImage& linear, ToneMap toneMap, float exposure, bool keepAlpha);

// Encodes a linear image in the request's format on the CPU (PNG: tone-mapped sRGB by toDisplay8;
// EXR: linear). Rendered frames come display-encoded by the GPU instead: see encodeFrame
// (frame_pixels.hpp).
std::vector<std::uint8_t> encodeImage(const FloatImage& linear, const OutputSettings& output,
                                      const ImageMetadata& metadata = {});
const char* mimeType(ImageFormat format);
const char* fileExtension(ImageFormat format);

}  // namespace lgh
