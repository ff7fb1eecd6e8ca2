// The mip chain a GPU's blit to half size gives (glGenerateMipmap), built on the CPU for a CPU
// rasteriser whose own is slow (TextureCapabilities::mipmapsOnCpu in scene/texture_upload.hpp):
// llvmpipe blits level by level, flushing and waiting for each level on its rasteriser threads.
// Plain CPU data, no GL.
#pragma once

#include <vector>

#include "lgh/image.hpp"

namespace lgh {

// The levels of `image` (RGBA8) below level 0, halving to 1 x 1: bilinear samples at the texels'
// centres (the mean of each 2x2 block where the sides are even), data rounded as llvmpipe's blit
// rounds it (the same bytes as its glGenerateMipmap), sRGB colour (`srgb`) averaged in linear
// light and rounded to the nearest code.
std::vector<Image8> buildBlitMipChain(const Image8& image, bool srgb);

}  // namespace lgh
