#include "scene/block_compression.hpp"

#include <array>

namespace lgh {
namespace {

using Rgba = std::array<std::uint8_t, 4>;

std::uint32_t read16(const std::uint8_t* bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8U);
}

std::uint32_t read32(const std::uint8_t* bytes) {
  return read16(bytes) | (read16(bytes + 2) << 16U);
}

std::uint64_t read48(const std::uint8_t* bytes) {
  std::uint64_t value = 0;
  for (int i = 5; i >= 0; --i) value = (value << 8U) | bytes[i];
  return value;
}

// RGB565 to 8 bits per channel, replicating the top bits into the bottom ones.
Rgba expand565(std::uint32_t c) {
  const auto r = static_cast<std::uint8_t>((c >> 11U) & 31U);
  const auto g = static_cast<std::uint8_t>((c >> 5U) & 63U);
  const auto b = static_cast<std::uint8_t>(c & 31U);
  return {static_cast<std::uint8_t>((r << 3U) | (r >> 2U)),
          static_cast<std::uint8_t>((g << 2U) | (g >> 4U)),
          static_cast<std::uint8_t>((b << 3U) | (b >> 2U)), 255};
}

std::uint8_t mix(std::uint32_t a, std::uint32_t b, std::uint32_t wa, std::uint32_t wb) {
  return static_cast<std::uint8_t>((a * wa + b * wb) / (wa + wb));
}

// The colour block shared by BC1-BC3: 4 texels' palette of two endpoints and two mixes, or (BC1
// with c0 <= c1) three colours and transparent black.
std::array<Rgba, 16> decodeColorBlock(const std::uint8_t* block, bool allowPunchThrough) {
  const std::uint32_t c0 = read16(block);
  const std::uint32_t c1 = read16(block + 2);
  const Rgba e0 = expand565(c0);
  const Rgba e1 = expand565(c1);
  std::array<Rgba, 4> palette{e0, e1, e0, e1};
  const bool fourColors = c0 > c1 || !allowPunchThrough;
  for (int c = 0; c < 3; ++c) {
    if (fourColors) {
      palette[2][c] = mix(e0[c], e1[c], 2, 1);
      palette[3][c] = mix(e0[c], e1[c], 1, 2);
    } else {
      palette[2][c] = mix(e0[c], e1[c], 1, 1);
      palette[3][c] = 0;
    }
  }
  palette[3][3] = fourColors ? 255 : 0;
  const std::uint32_t indices = read32(block + 4);
  std::array<Rgba, 16> texels{};
  for (std::uint32_t i = 0; i < 16; ++i) texels[i] = palette[(indices >> (2U * i)) & 3U];
  return texels;
}

// BC4's block (also BC3's alpha, BC5's two channels): two endpoints, 3-bit indices into 8 values.
std::array<std::uint8_t, 16> decodeChannelBlock(const std::uint8_t* block) {
  const std::uint32_t a0 = block[0];
  const std::uint32_t a1 = block[1];
  std::array<std::uint8_t, 8> values{static_cast<std::uint8_t>(a0), static_cast<std::uint8_t>(a1)};
  if (a0 > a1) {
    for (std::uint32_t i = 1; i < 7; ++i) {
      values[i + 1] = static_cast<std::uint8_t>(((7 - i) * a0 + i * a1) / 7);
    }
  } else {
    for (std::uint32_t i = 1; i < 5; ++i) {
      values[i + 1] = static_cast<std::uint8_t>(((5 - i) * a0 + i * a1) / 5);
    }
    values[6] = 0;
    values[7] = 255;
  }
  const std::uint64_t indices = read48(block + 2);
  std::array<std::uint8_t, 16> texels{};
  for (std::uint32_t i = 0; i < 16; ++i) texels[i] = values[(indices >> (3U * i)) & 7U];
  return texels;
}

std::array<Rgba, 16> decodeBlock(BlockFormat format, const std::uint8_t* block) {
  std::array<Rgba, 16> texels{};
  switch (format) {
    case BlockFormat::Bc1:
      return decodeColorBlock(block, true);
    case BlockFormat::Bc2: {
      texels = decodeColorBlock(block + 8, false);
      for (std::uint32_t i = 0; i < 16; ++i) {
        const std::uint32_t nibble = (block[i / 2] >> (4U * (i % 2))) & 15U;
        texels[i][3] = static_cast<std::uint8_t>(nibble * 17);
      }
      return texels;
    }
    case BlockFormat::Bc3: {
      texels = decodeColorBlock(block + 8, false);
      const auto alpha = decodeChannelBlock(block);
      for (std::size_t i = 0; i < 16; ++i) texels[i][3] = alpha[i];
      return texels;
    }
    case BlockFormat::Bc4: {
      const auto red = decodeChannelBlock(block);
      for (std::size_t i = 0; i < 16; ++i) texels[i] = {red[i], red[i], red[i], 255};
      return texels;
    }
    case BlockFormat::Bc5: {
      const auto red = decodeChannelBlock(block);
      const auto green = decodeChannelBlock(block + 8);
      for (std::size_t i = 0; i < 16; ++i) texels[i] = {red[i], green[i], 0, 255};
      return texels;
    }
  }
  return texels;
}

}  // namespace

const char* blockFormatName(BlockFormat format) {
  switch (format) {
    case BlockFormat::Bc1:
      return "BC1";
    case BlockFormat::Bc2:
      return "BC2";
    case BlockFormat::Bc3:
      return "BC3";
    case BlockFormat::Bc4:
      return "BC4";
    case BlockFormat::Bc5:
      return "BC5";
  }
  return "?";
}

std::size_t blockBytes(BlockFormat format) {
  return format == BlockFormat::Bc1 || format == BlockFormat::Bc4 ? 8 : 16;
}

std::size_t blockLevelBytes(BlockFormat format, int width, int height) {
  const auto blocksX = static_cast<std::size_t>((width + 3) / 4);
  const auto blocksY = static_cast<std::size_t>((height + 3) / 4);
  return blocksX * blocksY * blockBytes(format);
}

Image8 decodeBlocks(BlockFormat format, int width, int height, const std::uint8_t* data) {
  Image8 image;
  image.width = width;
  image.height = height;
  image.channels = 4;
  image.pixels.resize(static_cast<std::size_t>(width) * height * 4);
  const int blocksX = (width + 3) / 4;
  const int blocksY = (height + 3) / 4;
  for (int by = 0; by < blocksY; ++by) {
    for (int bx = 0; bx < blocksX; ++bx) {
      const std::uint8_t* block =
          data + (static_cast<std::size_t>(by) * blocksX + bx) * blockBytes(format);
      const auto texels = decodeBlock(format, block);
      for (int i = 0; i < 16; ++i) {
        const int x = bx * 4 + i % 4;
        const int y = by * 4 + i / 4;
        if (x >= width || y >= height) continue;
        std::uint8_t* pixel = &image.pixels[(static_cast<std::size_t>(y) * width + x) * 4];
        for (int c = 0; c < 4; ++c) pixel[c] = texels[static_cast<std::size_t>(i)][c];
      }
    }
  }
  return image;
}

}  // namespace lgh
