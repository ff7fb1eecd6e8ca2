#include "scene/gltf/webp_decoding.hpp"

#include <cstring>
#include <memory>

#include <fmt/format.h>
#include <webp/decode.h>

namespace lgh::gltf {

bool isWebp(const std::uint8_t* bytes, std::size_t size) {
  return size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
}

std::optional<std::pair<std::uint32_t, std::uint32_t>> webpSize(const std::uint8_t* bytes,
                                                                std::size_t size) {
  int width = 0;
  int height = 0;
  if (WebPGetInfo(bytes, size, &width, &height) == 0 || width <= 0 || height <= 0) {
    return std::nullopt;
  }
  return std::make_pair(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
}

Image8 decodeWebp(const LoadContext& ctx, const std::uint8_t* bytes, std::size_t size,
                  const std::string& what) {
  int width = 0;
  int height = 0;
  const std::unique_ptr<std::uint8_t, decltype(&WebPFree)> pixels(
      WebPDecodeRGBA(bytes, size, &width, &height), &WebPFree);
  if (pixels == nullptr || width <= 0 || height <= 0) {
    invalid(ctx, fmt::format("{}: not a valid WebP stream", what));
  }
  Image8 image;
  image.width = width;
  image.height = height;
  image.channels = 4;
  image.pixels.assign(pixels.get(), pixels.get() + static_cast<std::size_t>(width) * height * 4);
  return image;
}

}  // namespace lgh::gltf
