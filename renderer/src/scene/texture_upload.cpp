#include "scene/texture_upload.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "gl/software_rasterizer.hpp"
#include "lgh/error.hpp"
#include "scene/blit_mip_chain.hpp"

namespace lgh {
namespace {

// Block-compressed internal formats (EXT_texture_compression_s3tc, EXT_texture_sRGB, RGTC).
constexpr GLenum kBc1 = 0x83F1;      // GL_COMPRESSED_RGBA_S3TC_DXT1_EXT
constexpr GLenum kBc2 = 0x83F2;      // GL_COMPRESSED_RGBA_S3TC_DXT3_EXT
constexpr GLenum kBc3 = 0x83F3;      // GL_COMPRESSED_RGBA_S3TC_DXT5_EXT
constexpr GLenum kBc1Srgb = 0x8C4D;  // GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT
constexpr GLenum kBc2Srgb = 0x8C4E;  // GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT3_EXT
constexpr GLenum kBc3Srgb = 0x8C4F;  // GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT
constexpr GLenum kBc4 = 0x8DBB;      // GL_COMPRESSED_RED_RGTC1
constexpr GLenum kBc5 = 0x8DBD;      // GL_COMPRESSED_RG_RGTC2

int mipLevels(int width, int height) {
  return 1 + static_cast<int>(std::floor(std::log2(static_cast<float>(std::max(width, height)))));
}

std::size_t rgba8Bytes(int width, int height, int levels) {
  std::size_t bytes = 0;
  for (int level = 0; level < levels; ++level) {
    bytes +=
        static_cast<std::size_t>(std::max(width >> level, 1)) * std::max(height >> level, 1) * 4;
  }
  return bytes;
}

float srgbToLinear(float c) {
  return c <= 0.04045F ? c / 12.92F : std::pow((c + 0.055F) / 1.055F, 2.4F);
}

float linearToSrgb(float c) {
  return c <= 0.0031308F ? c * 12.92F : 1.055F * std::pow(c, 1.0F / 2.4F) - 0.055F;
}

bool hasTranslucency(const Image8& image) {
  for (std::size_t i = 3; i < image.pixels.size(); i += 4) {
    if (image.pixels[i] != 255) return true;
  }
  return false;
}

GLenum blockEnum(BlockFormat format, bool srgb) {
  switch (format) {
    case BlockFormat::Bc1:
      return srgb ? kBc1Srgb : kBc1;
    case BlockFormat::Bc2:
      return srgb ? kBc2Srgb : kBc2;
    case BlockFormat::Bc3:
      return srgb ? kBc3Srgb : kBc3;
    case BlockFormat::Bc4:
      return kBc4;
    case BlockFormat::Bc5:
      return kBc5;
  }
  return kBc1;
}

std::string formatName(BlockFormat format, bool srgb) {
  return std::string(blockFormatName(format)) + (srgb ? " sRGB" : "");
}

// The GPU bytes of a compressed texture's levels, as the driver reports them (the lecture's
// GL_TEXTURE_COMPRESSED_IMAGE_SIZE), after checking that it did compress.
std::size_t compressedBytes(GLuint texture, int levels) {
  GLint isCompressed = 0;
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_COMPRESSED, &isCompressed);
  if (isCompressed == 0) {
    throw Error(ErrorCode::Internal, "the driver stored a compressed format uncompressed",
                "texture upload");
  }
  std::size_t bytes = 0;
  for (int level = 0; level < levels; ++level) {
    GLint size = 0;
    glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_COMPRESSED_IMAGE_SIZE, &size);
    bytes += static_cast<std::size_t>(std::max(size, 0));
  }
  return bytes;
}

void setLevelRange(GLuint texture, int levels) {
  glTextureParameteri(texture, GL_TEXTURE_BASE_LEVEL, 0);
  glTextureParameteri(texture, GL_TEXTURE_MAX_LEVEL, levels - 1);
}

UploadedTexture uploadPlain(const Image8& image, bool srgb, bool mipmapsOnCpu,
                            const StagedPixels* staged, gl::RecycledTextures* recycled,
                            const std::vector<Image8>* mipChain) {
  UploadedTexture result;
  const int levels = mipLevels(image.width, image.height);
  result.bytes = rgba8Bytes(image.width, image.height, levels);
  const gl::TextureShape shape{srgb ? GLenum{GL_SRGB8_ALPHA8} : GLenum{GL_RGBA8}, image.width,
                               image.height, levels};
  result.texture = gl::takeStorage(recycled, shape, result.bytes);
  const GLuint id = result.texture.id();
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (staged != nullptr) {
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, staged->buffer);
    glTextureSubImage2D(id, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                        reinterpret_cast<const void*>(staged->offset));  // NOLINT: GL's offset
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  } else {
    glTextureSubImage2D(id, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                        image.pixels.data());
  }
  if (mipmapsOnCpu) {
    const std::vector<Image8> built =
        mipChain == nullptr ? buildBlitMipChain(image, srgb) : std::vector<Image8>{};
    const std::vector<Image8>& chain = mipChain == nullptr ? built : *mipChain;
    for (std::size_t i = 0; i < chain.size(); ++i) {
      const Image8& level = chain[i];
      glTextureSubImage2D(id, static_cast<GLint>(i + 1), 0, 0, level.width, level.height, GL_RGBA,
                          GL_UNSIGNED_BYTE, level.pixels.data());
    }
  } else {
    glGenerateTextureMipmap(id);
  }
  result.uncompressedBytes = result.bytes;
  result.format = srgb ? "SRGB8_ALPHA8" : "RGBA8";
  return result;
}

// Compression on upload: the driver encodes each level of the CPU-built chain.
UploadedTexture uploadCompressing(const Image8& image, BlockFormat format, bool srgb) {
  UploadedTexture result;
  result.texture = gl::RecycledTexture(gl::Texture(GL_TEXTURE_2D));
  const int levels = mipLevels(image.width, image.height);
  const GLuint id = result.texture.id();
  glTextureStorage2D(id, levels, blockEnum(format, srgb), image.width, image.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(id, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                      image.pixels.data());
  const std::vector<Image8> chain = buildMipChain(image, srgb);
  for (std::size_t i = 0; i < chain.size(); ++i) {
    const Image8& level = chain[i];
    glTextureSubImage2D(id, static_cast<GLint>(i + 1), 0, 0, level.width, level.height, GL_RGBA,
                        GL_UNSIGNED_BYTE, level.pixels.data());
  }
  setLevelRange(id, levels);
  result.bytes = compressedBytes(id, levels);
  result.uncompressedBytes = rgba8Bytes(image.width, image.height, levels);
  result.compressed = true;
  result.twoChannel = format == BlockFormat::Bc5;
  result.format = formatName(format, srgb);
  return result;
}

// Blocks as loaded: uploaded as they are, with the file's mip levels. A file with level 0 alone
// gets the rest of the chain as compression on upload makes it (decoded, box-filtered, compressed
// by the driver): minified, it would alias otherwise.
UploadedTexture uploadBlocks(const BlockCompressedImage& blocks, bool srgb) {
  UploadedTexture result;
  result.texture = gl::RecycledTexture(gl::Texture(GL_TEXTURE_2D));
  const auto fileLevels = static_cast<int>(blocks.levels.size());
  const int levels = fileLevels == 1 ? mipLevels(blocks.width, blocks.height) : fileLevels;
  const GLuint id = result.texture.id();
  const GLenum internalFormat = blockEnum(blocks.format, srgb);
  glTextureStorage2D(id, levels, internalFormat, blocks.width, blocks.height);
  for (int level = 0; level < fileLevels; ++level) {
    const auto& data = blocks.levels[static_cast<std::size_t>(level)];
    glCompressedTextureSubImage2D(id, level, 0, 0, std::max(blocks.width >> level, 1),
                                  std::max(blocks.height >> level, 1), internalFormat,
                                  static_cast<GLsizei>(data.size()), data.data());
  }
  if (levels > fileLevels) {
    const Image8 decoded =
        decodeBlocks(blocks.format, blocks.width, blocks.height, blocks.levels.front().data());
    const std::vector<Image8> chain = buildMipChain(decoded, srgb);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (std::size_t i = 0; i < chain.size(); ++i) {
      glTextureSubImage2D(id, static_cast<GLint>(i + 1), 0, 0, chain[i].width, chain[i].height,
                          GL_RGBA, GL_UNSIGNED_BYTE, chain[i].pixels.data());
    }
  }
  setLevelRange(id, levels);
  result.bytes = compressedBytes(id, levels);
  result.uncompressedBytes = rgba8Bytes(blocks.width, blocks.height, levels);
  result.compressed = true;
  result.twoChannel = blocks.format == BlockFormat::Bc5;
  result.format = formatName(blocks.format, srgb);
  return result;
}

// What compression on upload makes of a use: colour and data in BC1 (BC3 where alpha matters),
// one channel in BC4, normal maps in BC5.
BlockFormat compressedFormat(const Image8& image, TextureUsage usage) {
  switch (usage) {
    case TextureUsage::Normal:
      return BlockFormat::Bc5;
    case TextureUsage::SingleChannel:
      return BlockFormat::Bc4;
    case TextureUsage::Color:
    case TextureUsage::Data:
      break;
  }
  return hasTranslucency(image) ? BlockFormat::Bc3 : BlockFormat::Bc1;
}

}  // namespace

namespace {

// GL 4.3's internal format query: whether the driver takes the format for 2D textures at all.
bool formatSupported(GLenum format) {
  GLint supported = GL_FALSE;
  glGetInternalformativ(GL_TEXTURE_2D, format, GL_INTERNALFORMAT_SUPPORTED, 1, &supported);
  return supported == GL_TRUE;
}

}  // namespace

TextureCapabilities TextureCapabilities::query() {
  TextureCapabilities capabilities;
  capabilities.s3tc = gl::api("extension flags").EXT_texture_compression_s3tc != 0 &&
                      formatSupported(kBc1) && formatSupported(kBc3);
  capabilities.s3tcSrgb =
      capabilities.s3tc && formatSupported(kBc1Srgb) && formatSupported(kBc3Srgb);
  capabilities.mipmapsOnCpu = gl::softwareRasterizer();
  return capabilities;
}

std::vector<Image8> buildMipChain(const Image8& image, bool srgb) {
  std::vector<Image8> chain;
  const Image8* previous = &image;
  while (previous->width > 1 || previous->height > 1) {
    Image8 next;
    next.width = std::max(previous->width / 2, 1);
    next.height = std::max(previous->height / 2, 1);
    next.channels = 4;
    next.pixels.resize(static_cast<std::size_t>(next.width) * next.height * 4);
    for (int y = 0; y < next.height; ++y) {
      for (int x = 0; x < next.width; ++x) {
        std::array<float, 4> sum{};
        int count = 0;
        for (int dy = 0; dy < 2; ++dy) {
          for (int dx = 0; dx < 2; ++dx) {
            const int sx = std::min(x * 2 + dx, previous->width - 1);
            const int sy = std::min(y * 2 + dy, previous->height - 1);
            const std::uint8_t* p =
                &previous->pixels[(static_cast<std::size_t>(sy) * previous->width + sx) * 4];
            for (int c = 0; c < 4; ++c) {
              const float value = static_cast<float>(p[c]) / 255.0F;
              sum[static_cast<std::size_t>(c)] += srgb && c < 3 ? srgbToLinear(value) : value;
            }
            ++count;
          }
        }
        std::uint8_t* out = &next.pixels[(static_cast<std::size_t>(y) * next.width + x) * 4];
        for (int c = 0; c < 4; ++c) {
          float value = sum[static_cast<std::size_t>(c)] / static_cast<float>(count);
          if (srgb && c < 3) value = linearToSrgb(value);
          out[c] = static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0F, 1.0F) * 255.0F));
        }
      }
    }
    chain.push_back(std::move(next));
    previous = &chain.back();
  }
  return chain;
}

UploadedTexture uploadTexture(const Image8& image, const BlockCompressedImage* precompressed,
                              TextureUsage usage, TextureCompression compression,
                              const TextureCapabilities& capabilities,
                              std::vector<std::string>& warnings, const StagedPixels* staged,
                              gl::RecycledTextures* recycled, const std::vector<Image8>* mipChain) {
  const bool srgb = usage == TextureUsage::Color;
  if (precompressed != nullptr) {
    const bool colorBlocks = precompressed->format <= BlockFormat::Bc3;
    const bool srgbUsable = !srgb || (colorBlocks && capabilities.s3tcSrgb);
    if ((colorBlocks && !capabilities.s3tc) || !srgbUsable) {
      warnings.push_back(
          fmt::format("a {} texture used as {}: the device cannot sample it so; uploaded decoded",
                      blockFormatName(precompressed->format), srgb ? "sRGB colour" : "data"));
    } else {
      return uploadBlocks(*precompressed, srgb);
    }
  }
  if (compression == TextureCompression::Bc) {
    const BlockFormat format = compressedFormat(image, usage);
    const bool colorBlocks = format <= BlockFormat::Bc3;
    if (colorBlocks && (!capabilities.s3tc || (srgb && !capabilities.s3tcSrgb))) {
      warnings.push_back(fmt::format(
          "texture_compression bc: the device has no {}{}; that texture stays uncompressed",
          blockFormatName(format), srgb ? " sRGB" : ""));
    } else {
      return uploadCompressing(image, format, srgb);
    }
  }
  return uploadPlain(image, srgb, capabilities.mipmapsOnCpu, staged, recycled, mipChain);
}

}  // namespace lgh
