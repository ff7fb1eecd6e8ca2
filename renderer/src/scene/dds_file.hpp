// DDS files holding BC1-BC5 textures (glTF's MSFT_texture_dds): the legacy header with a FourCC
// (DXT1, DXT2/3, DXT4/5, ATI1/BC4U, ATI2/BC5U) or the DX10 header with a DXGI format (BC1-BC5,
// UNORM and sRGB). 2D textures only, with their mip levels. Every size is checked against the
// file before anything is read or allocated: DDS files come from requests.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/block_compression.hpp"

namespace lgh {

bool isDds(const std::uint8_t* bytes, std::size_t size);

// The texture's size from its header, or nothing when the header is incomplete.
std::optional<std::pair<std::uint32_t, std::uint32_t>> ddsSize(const std::uint8_t* bytes,
                                                               std::size_t size);

// Parses a DDS file. Throws lgh::Error(Invalid) naming `what` and the problem (truncated, not 2D,
// unsupported format, sizes that do not fit the file).
BlockCompressedImage readDds(const std::uint8_t* bytes, std::size_t size, const std::string& what);

// A DDS file for `image` (FourCC header for UNORM, DX10 header for sRGB): tests and tools.
std::vector<std::uint8_t> writeDds(const BlockCompressedImage& image);

}  // namespace lgh
