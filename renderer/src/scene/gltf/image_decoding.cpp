#include "scene/gltf/image_decoding.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "lgh/error.hpp"
#include "lgh/image.hpp"
#include "scene/dds_file.hpp"
#include "scene/gltf/load_context.hpp"
#include "scene/gltf/webp_decoding.hpp"

namespace lgh::gltf {
namespace {

std::uint32_t readBigEndian(const std::uint8_t* bytes, int count) {
  std::uint32_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8U) | bytes[i];
  return value;
}

// JPEG frame size from the first SOFn marker, without decoding.
std::optional<std::pair<std::uint32_t, std::uint32_t>> jpegSize(const std::uint8_t* bytes,
                                                                std::size_t size) {
  std::size_t i = 2;
  while (i + 4 <= size) {
    if (bytes[i] != 0xFF) return std::nullopt;
    const std::uint8_t marker = bytes[i + 1];
    if (marker == 0xFF) {  // fill byte
      ++i;
      continue;
    }
    i += 2;
    const bool standalone = marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8);
    if (standalone) continue;
    if (marker == 0xD9 || marker == 0xDA) return std::nullopt;  // no frame header before scan
    const std::uint32_t length = readBigEndian(bytes + i, 2);
    const bool frame =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (frame) {
      if (i + 7 > size) return std::nullopt;
      return std::make_pair(readBigEndian(bytes + i + 5, 2), readBigEndian(bytes + i + 3, 2));
    }
    if (length < 2) return std::nullopt;
    i += length;
  }
  return std::nullopt;
}

// Width and height from a PNG or JPEG header, so that an oversized texture is refused before
// the decoder allocates for it (a small file can claim 65535 x 65535 pixels).
std::optional<std::pair<std::uint32_t, std::uint32_t>> sniffImageSize(const std::uint8_t* bytes,
                                                                      std::size_t size) {
  static constexpr std::uint8_t kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (size >= 24 && std::memcmp(bytes, kPng, 8) == 0 && std::memcmp(bytes + 12, "IHDR", 4) == 0) {
    return std::make_pair(readBigEndian(bytes + 16, 4), readBigEndian(bytes + 20, 4));
  }
  if (size >= 4 && bytes[0] == 0xFF && bytes[1] == 0xD8) return jpegSize(bytes, size);
  if (isWebp(bytes, size)) return webpSize(bytes, size);
  if (isDds(bytes, size)) return ddsSize(bytes, size);
  return std::nullopt;
}

void checkTextureSize(const LoadContext& ctx, std::uint64_t width, std::uint64_t height,
                      const std::string& what) {
  const auto limit = static_cast<std::uint64_t>(std::max(ctx.limits.maxTextureSize, 0));
  if (width > limit || height > limit) {
    tooLarge(ctx,
             fmt::format("{} is {} x {} pixels, over the limit of {}", what, width, height, limit));
  }
  // Both at most maxTextureSize (< 2^31): the product cannot overflow.
  const std::uint64_t bytes = width * height * 4;
  if (bytes >
      ctx.limits.maxTextureBytes - std::min(ctx.decodedTextureBytes, ctx.limits.maxTextureBytes)) {
    tooLarge(ctx, fmt::format("{} ({} x {} pixels) takes the asset's textures past the limit of "
                              "{} bytes decoded",
                              what, width, height, ctx.limits.maxTextureBytes));
  }
}

Image8 decodeTexture(LoadContext& ctx, const std::uint8_t* bytes, std::size_t size,
                     const std::string& what) {
  if (bytes == nullptr || size == 0) invalid(ctx, fmt::format("{} has no data", what));
  if (const auto header = sniffImageSize(bytes, size)) {
    checkTextureSize(ctx, header->first, header->second, what);
  }
  Image8 image;
  try {
    image = isWebp(bytes, size) ? decodeWebp(ctx, bytes, size, what)
                                : image_io::decodeTextureRgba8(bytes, size, what);
  } catch (const Error& error) {
    if (error.code() == ErrorCode::TooLarge) throw;
    invalid(ctx, fmt::format("{} could not be decoded: {}", what, error.message()));
  }
  checkTextureSize(ctx, static_cast<std::uint64_t>(std::max(image.width, 0)),
                   static_cast<std::uint64_t>(std::max(image.height, 0)), what);
  const auto expected = static_cast<std::size_t>(image.width) * image.height * 4;
  if (image.width <= 0 || image.height <= 0 || image.channels != 4 ||
      image.pixels.size() != expected) {
    invalid(ctx, fmt::format("{} decoded to an unusable image", what));
  }
  ctx.decodedTextureBytes += expected;
  return image;
}

}  // namespace

std::string imageLabel(const tinygltf::Image& image, int index) {
  std::string text = label("images", index, image.name);
  if (!image.uri.empty()) text += fmt::format(" '{}'", image.uri);
  return text;
}

bool loadImageCallback(tinygltf::Image* image, const int index, std::string*, std::string*, int,
                       int, const unsigned char* bytes, int size, void* user) {
  auto& ctx = *static_cast<LoadContext*>(user);
  const std::string what = imageLabel(*image, index);
  try {
    if (size <= 0) invalid(ctx, fmt::format("{} has no data", what));
    const auto length = static_cast<std::size_t>(size);
    if (isDds(bytes, length)) {
      // MSFT_texture_dds: the blocks go to the GPU as they are; the CPU keeps them decoded.
      if (const auto header = ddsSize(bytes, length)) {
        checkTextureSize(ctx, header->first, header->second, what);
      }
      BlockCompressedImage blocks = readDds(bytes, length, what);
      Image8 decoded =
          decodeBlocks(blocks.format, blocks.width, blocks.height, blocks.levels.front().data());
      image->width = decoded.width;
      image->height = decoded.height;
      image->component = 4;
      image->bits = 8;
      image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
      ctx.images.insert_or_assign(index, std::move(decoded));
      ctx.blockImages.insert_or_assign(index, std::move(blocks));
      return true;
    }
    Image8 decoded = decodeTexture(ctx, bytes, length, what);
    image->width = decoded.width;
    image->height = decoded.height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    ctx.images.insert_or_assign(index, std::move(decoded));
  } catch (const Error& error) {
    ctx.imageErrors.insert_or_assign(index, error);
  } catch (const std::bad_alloc&) {
    ctx.imageErrors.insert_or_assign(
        index, Error(ErrorCode::TooLarge, what + " is too large to decode", ctx.displayName));
  }
  return true;
}

}  // namespace lgh::gltf
