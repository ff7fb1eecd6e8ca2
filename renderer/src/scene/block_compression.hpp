// Block-compressed textures (BC1-BC5, a.k.a. S3TC DXT1/3/5 and RGTC1/2 or 3Dc): what a
// precompressed image holds, the block sizes, and a CPU decoder. The GPU samples the blocks as they
// are; the decoder gives the CPU the same texels (VPL colours, tests) and is the reference the
// tests compare the driver's compression with.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lgh/image.hpp"

namespace lgh {

enum class BlockFormat : std::uint8_t {
  Bc1,  // RGB (+1-bit alpha), 8 bytes per 4x4 block
  Bc2,  // RGB + explicit 4-bit alpha, 16 bytes
  Bc3,  // RGB + interpolated alpha, 16 bytes
  Bc4,  // one channel (R), 8 bytes
  Bc5,  // two channels (RG): normal maps, 16 bytes
};

const char* blockFormatName(BlockFormat format);
std::size_t blockBytes(BlockFormat format);
// Bytes of one mip level of width x height texels (whole 4x4 blocks).
std::size_t blockLevelBytes(BlockFormat format, int width, int height);

struct BlockCompressedImage {
  BlockFormat format = BlockFormat::Bc1;
  bool srgb = false;  // the file says its colour is sRGB-encoded (DXGI *_SRGB formats)
  int width = 0;
  int height = 0;
  std::vector<std::vector<std::uint8_t>> levels;  // level 0 first, each blockLevelBytes long
};

// Decodes one level to RGBA8 (BC4: R in red, green and blue; BC5: R, G, blue 0; alpha 255 where
// the format has none). `data` must hold blockLevelBytes(format, width, height) bytes.
Image8 decodeBlocks(BlockFormat format, int width, int height, const std::uint8_t* data);

}  // namespace lgh
