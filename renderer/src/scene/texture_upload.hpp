// One scene image as a GL texture for one use (TextureUsage): RGBA8 as decoded, or block-
// compressed - on upload (settings.texture_compression "bc": the driver compresses each level of
// a mip chain built here, as the lecture's glTexImage2D with a GL_COMPRESSED_* internal format),
// or as loaded (DDS, MSFT_texture_dds). GL cannot generate mip levels of a compressed texture
// (glGenerateMipmap needs a renderable format), so compressed chains are built on the CPU with a
// 2x2 box filter (sRGB colour averaged in linear light).
#pragma once

#include <cstddef>
#include <string>

#include "gl/gl_objects.hpp"
#include "gl/recycled_objects.hpp"
#include "lgh/request.hpp"
#include "scene/block_compression.hpp"
#include "scene/scene.hpp"

namespace lgh {

struct UploadedTexture {
  gl::RecycledTexture texture;
  std::size_t bytes = 0;              // GPU bytes, every level (compressed: the driver's sizes)
  std::size_t uncompressedBytes = 0;  // what the RGBA8 texture would take
  bool compressed = false;
  bool twoChannel = false;  // BC5 normal map: the shader rebuilds z
  std::string format;       // "RGBA8", "SRGB8_ALPHA8", "BC1", "BC3 sRGB", ...
};

// What the device can do, asked once per scene upload.
struct TextureCapabilities {
  bool s3tc = false;      // BC1-BC3
  bool s3tcSrgb = false;  // BC1-BC3 with sRGB decoding
  // Mip chains built by buildBlitMipChain, not glGenerateMipmap: a CPU rasteriser (llvmpipe) blits
  // each level, flushing and waiting for the one before it on the rasteriser threads, which cost
  // the VM's cold thumbnails about 9 % (docs/BENCHMARKS.md).
  bool mipmapsOnCpu = false;
  static TextureCapabilities query();
};

// The image's RGBA8 pixels in a GL buffer (scene/staged_scene.hpp): level 0 is then copied from
// there by the GPU instead of from `image` by the calling thread.
struct StagedPixels {
  GLuint buffer = 0;
  GLintptr offset = 0;
};

// `precompressed` (may be null): the image's blocks as loaded. `staged` (may be null): used when
// the texture is uploaded as decoded RGBA8. `recycled` (may be null): where an RGBA8 texture
// takes its storage (block-compressed ones have storage of their own). `mipChain` (may be null):
// on a CPU rasteriser, the levels below 0 built ahead (scene/scene_mip_chains.hpp), else built
// here. Throws lgh::Error(Internal)
// when the driver refuses a compressed upload it claims to support. Warnings (a usage the blocks
// cannot serve, a format the device lacks) go to `warnings`.
UploadedTexture uploadTexture(const Image8& image, const BlockCompressedImage* precompressed,
                              TextureUsage usage, TextureCompression compression,
                              const TextureCapabilities& capabilities,
                              std::vector<std::string>& warnings,
                              const StagedPixels* staged = nullptr,
                              gl::RecycledTextures* recycled = nullptr,
                              const std::vector<Image8>* mipChain = nullptr);

// The mip chain of `image` below level 0, halving to 1 x 1 (2x2 box filter; `srgb`: averaged in
// linear light): the levels that compression on upload encodes.
std::vector<Image8> buildMipChain(const Image8& image, bool srgb);

}  // namespace lgh
