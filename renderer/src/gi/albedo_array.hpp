// The scene's base-colour textures for shaders that read materials at ray hits
// (glsl/include/gi_material.glsl): every image a material uses as its base colour, downsampled
// (area average in linear light) or upsampled (nearest) to kAlbedoSize^2 and stored as one layer
// of an sRGB texture array. One array binds in any shader, whatever the number of textures; the
// cost is detail: at 256^2 a texture keeps its colours and coarse pattern, which is what a
// diffuse bounce's albedo needs (docs/GI.md). Also the linear mean colour of every image.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl_objects.hpp"
#include "scene/scene.hpp"

namespace lgh {

inline constexpr int kAlbedoSize = 256;

// An image resampled to size x size RGBA8 (sRGB in, sRGB out; averaged in linear light).
Image8 resampleImage(const Image8& image, int size);
// The mean colour of an image in linear light; white for an empty one.
glm::vec3 meanLinearColor(const Image8& image);

class AlbedoArray {
 public:
  // Layers for the base-colour images (of `scene`) of `materials`, at most `maxLayers` (the rest
  // get none: their materials use the factor alone, with a warning in `warnings`).
  AlbedoArray(const Scene& scene, const std::vector<Material>& materials, int maxLayers,
              std::vector<std::string>& warnings);

  // The layer of scene image `image`, -1 when it has none.
  int layerOf(int image) const;
  GLuint texture() const { return texture_.id(); }
  GLuint sampler() const { return sampler_.id(); }
  std::size_t gpuBytes() const { return gpuBytes_; }
  // Level 0 of every layer as the texture holds it (sRGB RGBA8, kAlbedoSize^2 per layer): what
  // Vulkan's light paths read in place of the texture (glsl/include/gi_material.glsl).
  std::span<const std::byte> texels() const { return std::as_bytes(std::span(texels_)); }

 private:
  std::vector<int> layerOfImage_;
  std::vector<std::uint8_t> texels_;
  gl::Texture texture_{GL_TEXTURE_2D_ARRAY};
  gl::SamplerObject sampler_;
  std::size_t gpuBytes_ = 0;
};

}  // namespace lgh
