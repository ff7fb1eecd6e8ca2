#include "scene/dds_file.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "lgh/error.hpp"

namespace lgh {
namespace {

// Offsets into the file (the 4-byte magic, then DDS_HEADER, then DDS_HEADER_DXT10 if present).
constexpr std::size_t kHeaderBytes = 4 + 124;
constexpr std::size_t kDx10Bytes = 20;
constexpr std::size_t kHeight = 4 + 8;
constexpr std::size_t kWidth = 4 + 12;
constexpr std::size_t kDepth = 4 + 20;
constexpr std::size_t kMipCount = 4 + 24;
constexpr std::size_t kPixelFormatFlags = 4 + 76;
constexpr std::size_t kFourCc = 4 + 80;
constexpr std::size_t kCaps2 = 4 + 108;
constexpr std::uint32_t kFourCcFlag = 0x4;
constexpr std::uint32_t kCaps2CubeOrVolume = 0x200 | 0x200000;
constexpr int kMaxSize = 1 << 16;

// DXGI_FORMAT values of BC1-BC5.
constexpr std::uint32_t kDxgiBc1 = 71, kDxgiBc1Srgb = 72, kDxgiBc2 = 74, kDxgiBc2Srgb = 75,
                        kDxgiBc3 = 77, kDxgiBc3Srgb = 78, kDxgiBc4 = 80, kDxgiBc5 = 83;
constexpr std::uint32_t kDimensionTexture2D = 3;

std::uint32_t read32(const std::uint8_t* bytes) {
  std::uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = (value << 8U) | bytes[i];
  return value;
}

void write32(std::vector<std::uint8_t>& out, std::size_t offset, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out[offset + i] = static_cast<std::uint8_t>(value >> (8U * i));
}

std::uint32_t fourCc(const char* text) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(text[0])) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(text[1])) << 8U) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(text[2])) << 16U) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(text[3])) << 24U);
}

[[noreturn]] void fail(const std::string& what, const std::string& problem) {
  throw Error(ErrorCode::Invalid, fmt::format("{} is not a usable DDS texture: {}", what, problem),
              what);
}

struct Format {
  BlockFormat format;
  bool srgb;
};

std::optional<Format> fromFourCc(std::uint32_t code) {
  if (code == fourCc("DXT1")) return Format{BlockFormat::Bc1, false};
  if (code == fourCc("DXT2") || code == fourCc("DXT3")) return Format{BlockFormat::Bc2, false};
  if (code == fourCc("DXT4") || code == fourCc("DXT5")) return Format{BlockFormat::Bc3, false};
  if (code == fourCc("ATI1") || code == fourCc("BC4U")) return Format{BlockFormat::Bc4, false};
  if (code == fourCc("ATI2") || code == fourCc("BC5U")) return Format{BlockFormat::Bc5, false};
  return std::nullopt;
}

std::optional<Format> fromDxgi(std::uint32_t dxgi) {
  switch (dxgi) {
    case kDxgiBc1:
      return Format{BlockFormat::Bc1, false};
    case kDxgiBc1Srgb:
      return Format{BlockFormat::Bc1, true};
    case kDxgiBc2:
      return Format{BlockFormat::Bc2, false};
    case kDxgiBc2Srgb:
      return Format{BlockFormat::Bc2, true};
    case kDxgiBc3:
      return Format{BlockFormat::Bc3, false};
    case kDxgiBc3Srgb:
      return Format{BlockFormat::Bc3, true};
    case kDxgiBc4:
      return Format{BlockFormat::Bc4, false};
    case kDxgiBc5:
      return Format{BlockFormat::Bc5, false};
    default:
      return std::nullopt;
  }
}

int fullMipCount(int width, int height) {
  int levels = 1;
  for (int size = std::max(width, height); size > 1; size /= 2) ++levels;
  return levels;
}

}  // namespace

bool isDds(const std::uint8_t* bytes, std::size_t size) {
  return size >= 4 && std::memcmp(bytes, "DDS ", 4) == 0;
}

std::optional<std::pair<std::uint32_t, std::uint32_t>> ddsSize(const std::uint8_t* bytes,
                                                               std::size_t size) {
  if (!isDds(bytes, size) || size < kHeaderBytes) return std::nullopt;
  return std::make_pair(read32(bytes + kWidth), read32(bytes + kHeight));
}

BlockCompressedImage readDds(const std::uint8_t* bytes, std::size_t size, const std::string& what) {
  if (!isDds(bytes, size)) fail(what, "no DDS magic");
  if (size < kHeaderBytes) fail(what, fmt::format("truncated header ({} bytes)", size));
  if (read32(bytes + 4) != 124) fail(what, "header size is not 124");
  const std::uint32_t width = read32(bytes + kWidth);
  const std::uint32_t height = read32(bytes + kHeight);
  if (width == 0 || height == 0 || width > kMaxSize || height > kMaxSize) {
    fail(what, fmt::format("size {} x {} is outside 1..{}", width, height, kMaxSize));
  }
  if ((read32(bytes + kCaps2) & kCaps2CubeOrVolume) != 0 || read32(bytes + kDepth) > 1) {
    fail(what, "cube maps and volume textures are not supported");
  }
  if ((read32(bytes + kPixelFormatFlags) & kFourCcFlag) == 0) {
    fail(what, "not block-compressed (no FourCC); only BC1-BC5 are supported");
  }
  std::size_t offset = kHeaderBytes;
  std::optional<Format> format;
  const std::uint32_t code = read32(bytes + kFourCc);
  if (code == fourCc("DX10")) {
    if (size < kHeaderBytes + kDx10Bytes) fail(what, "truncated DX10 header");
    const std::uint8_t* dx10 = bytes + kHeaderBytes;
    if (read32(dx10 + 4) != kDimensionTexture2D || read32(dx10 + 12) > 1) {
      fail(what, "only single 2D textures are supported (no arrays, no 1D or 3D)");
    }
    format = fromDxgi(read32(dx10));
    if (!format) fail(what, fmt::format("DXGI format {} is not BC1-BC5", read32(dx10)));
    offset += kDx10Bytes;
  } else {
    format = fromFourCc(code);
    if (!format) fail(what, "FourCC is not one of DXT1, DXT2-5, ATI1, BC4U, ATI2, BC5U");
  }
  const auto declaredLevels =
      static_cast<int>(std::max<std::uint32_t>(read32(bytes + kMipCount), 1));
  const int maxLevels = fullMipCount(static_cast<int>(width), static_cast<int>(height));
  if (declaredLevels > maxLevels) {
    fail(what, fmt::format("{} mip levels for a {} x {} texture (at most {})", declaredLevels,
                           width, height, maxLevels));
  }
  BlockCompressedImage image;
  image.format = format->format;
  image.srgb = format->srgb;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  int levelWidth = image.width;
  int levelHeight = image.height;
  for (int level = 0; level < declaredLevels; ++level) {
    const std::size_t bytesNeeded = blockLevelBytes(image.format, levelWidth, levelHeight);
    if (offset > size || size - offset < bytesNeeded) {
      fail(what, fmt::format("mip level {} needs {} bytes at offset {}, the file has {}", level,
                             bytesNeeded, offset, size));
    }
    image.levels.emplace_back(bytes + offset, bytes + offset + bytesNeeded);
    offset += bytesNeeded;
    levelWidth = std::max(levelWidth / 2, 1);
    levelHeight = std::max(levelHeight / 2, 1);
  }
  return image;
}

std::vector<std::uint8_t> writeDds(const BlockCompressedImage& image) {
  const bool dx10 = image.srgb;
  std::vector<std::uint8_t> out(kHeaderBytes + (dx10 ? kDx10Bytes : 0), 0);
  std::memcpy(out.data(), "DDS ", 4);
  write32(out, 4, 124);
  write32(out, 8, 0x1 | 0x2 | 0x4 | 0x1000 | 0x20000);  // CAPS HEIGHT WIDTH PIXELFORMAT MIPMAPCOUNT
  write32(out, kHeight, static_cast<std::uint32_t>(image.height));
  write32(out, kWidth, static_cast<std::uint32_t>(image.width));
  write32(out, 4 + 16,
          image.levels.empty() ? 0 : static_cast<std::uint32_t>(image.levels[0].size()));
  write32(out, kMipCount, static_cast<std::uint32_t>(image.levels.size()));
  write32(out, 4 + 72, 32);
  write32(out, kPixelFormatFlags, kFourCcFlag);
  static constexpr const char* kCodes[] = {"DXT1", "DXT3", "DXT5", "ATI1", "ATI2"};
  write32(out, kFourCc, fourCc(dx10 ? "DX10" : kCodes[static_cast<int>(image.format)]));
  write32(out, 4 + 104, 0x1000 | 0x400000 | 0x8);  // TEXTURE MIPMAP COMPLEX
  if (dx10) {
    static constexpr std::uint32_t kSrgb[] = {kDxgiBc1Srgb, kDxgiBc2Srgb, kDxgiBc3Srgb, kDxgiBc4,
                                              kDxgiBc5};
    write32(out, kHeaderBytes, kSrgb[static_cast<int>(image.format)]);
    write32(out, kHeaderBytes + 4, kDimensionTexture2D);
    write32(out, kHeaderBytes + 12, 1);
  }
  for (const auto& level : image.levels) out.insert(out.end(), level.begin(), level.end());
  return out;
}

}  // namespace lgh
