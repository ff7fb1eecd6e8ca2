#include "scene/procedural_textures.hpp"

#include <algorithm>
#include <cmath>

namespace lgh {
namespace {

Image8 blank(int width, int height) {
  Image8 image;
  image.width = width;
  image.height = height;
  image.channels = 4;
  image.pixels.assign(static_cast<std::size_t>(width) * height * 4, 255);
  return image;
}

std::uint8_t* texel(Image8& image, int x, int y) {
  return &image.pixels[(static_cast<std::size_t>(y) * image.width + x) * 4];
}

std::uint8_t toByte(float value) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0F, 1.0F) * 255.0F));
}

// A small deterministic hash noise in 0..1.
float noise(int x, int y) {
  auto h = static_cast<std::uint32_t>(x) * 374761393U + static_cast<std::uint32_t>(y) * 668265263U;
  h = (h ^ (h >> 13U)) * 1274126177U;
  return static_cast<float>((h ^ (h >> 16U)) & 0xFFFFU) / 65535.0F;
}

}  // namespace

Image8 makeCheckerImage(int size, int tiles, std::uint8_t light, std::uint8_t dark) {
  Image8 image = blank(size, size);
  const int tile = std::max(size / tiles, 1);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const std::uint8_t value = ((x / tile) + (y / tile)) % 2 == 0 ? light : dark;
      std::uint8_t* p = texel(image, x, y);
      p[0] = p[1] = p[2] = value;
    }
  }
  return image;
}

namespace {

// Where a texel lies in the brick pattern: the brick's number and the distance to its edge (in
// course heights, 0 at the mortar's middle).
struct BrickTexel {
  int brick;
  float edge;
};

BrickTexel brickAt(int x, int y, int size, int rows) {
  const float courseHeight = 1.0F / static_cast<float>(rows);
  const float brickWidth = 2.0F * courseHeight;
  const float u = (static_cast<float>(x) + 0.5F) / static_cast<float>(size);
  const float v = (static_cast<float>(y) + 0.5F) / static_cast<float>(size);
  const int course = static_cast<int>(v / courseHeight);
  const float shift = course % 2 == 0 ? 0.0F : 0.5F * brickWidth;
  const float shifted = u + shift;
  const int column = static_cast<int>(shifted / brickWidth);
  const float inU = std::fmod(shifted, brickWidth) / brickWidth;  // 0..1 across a brick
  const float inV = std::fmod(v, courseHeight) / courseHeight;
  return {course * 97 + column, std::min({inU * 2.0F, (1.0F - inU) * 2.0F, inV, 1.0F - inV})};
}

constexpr float kMortar = 0.08F;  // of a course
constexpr float kBevel = 0.12F;

}  // namespace

Image8 makeBrickColorImage(int size, int rows) {
  Image8 image = blank(size, size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const BrickTexel brick = brickAt(x, y, size, rows);
      std::uint8_t* p = texel(image, x, y);
      if (brick.edge < kMortar) {
        p[0] = p[1] = p[2] = toByte(0.72F + 0.06F * noise(x, y));
        continue;
      }
      const float shade = 0.8F + 0.2F * noise(brick.brick, 17) + 0.06F * noise(x, y);
      p[0] = toByte(0.62F * shade);
      p[1] = toByte(0.27F * shade);
      p[2] = toByte(0.18F * shade);
    }
  }
  return image;
}

Image8 makeHoleAlphaImage(int size, int cells) {
  Image8 image = blank(size, size);
  const float cell = static_cast<float>(size) / static_cast<float>(cells);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float cx = std::fmod(static_cast<float>(x) + 0.5F, cell) / cell - 0.5F;
      const float cy = std::fmod(static_cast<float>(y) + 0.5F, cell) / cell - 0.5F;
      const float radius = std::sqrt(cx * cx + cy * cy);
      texel(image, x, y)[3] = toByte((radius - 0.25F) / 0.1F);
    }
  }
  return image;
}

Image8 makeBrickHeightImage(int size, int rows) {
  Image8 image = blank(size, size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float edge = brickAt(x, y, size, rows).edge;
      float height = std::clamp((edge - kMortar) / kBevel, 0.0F, 1.0F);
      height *= 0.9F + 0.1F * noise(x, y);
      std::uint8_t* p = texel(image, x, y);
      p[0] = p[1] = p[2] = toByte(height);
    }
  }
  return image;
}

Image8 makeNormalMapImage(const Image8& height, float strength) {
  Image8 image = blank(height.width, height.height);
  auto h = [&](int x, int y) {
    x = (x + height.width) % height.width;
    y = (y + height.height) % height.height;
    return static_cast<float>(height.pixels[(static_cast<std::size_t>(y) * height.width + x) * 4]) /
           255.0F;
  };
  for (int y = 0; y < height.height; ++y) {
    for (int x = 0; x < height.width; ++x) {
      const float du = (h(x + 1, y) - h(x - 1, y)) * 0.5F * strength;
      const float dv = (h(x, y + 1) - h(x, y - 1)) * 0.5F * strength;
      // Image rows run down (+v); tangent-space +Y runs up the image.
      float nx = -du;
      float ny = dv;
      float nz = 1.0F;
      const float length = std::sqrt(nx * nx + ny * ny + nz * nz);
      nx /= length;
      ny /= length;
      nz /= length;
      std::uint8_t* p = texel(image, x, y);
      p[0] = toByte(nx * 0.5F + 0.5F);
      p[1] = toByte(ny * 0.5F + 0.5F);
      p[2] = toByte(nz * 0.5F + 0.5F);
    }
  }
  return image;
}

Image8 makeLightMapImage(int size) {
  Image8 image = blank(size, size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float u = (static_cast<float>(x) + 0.5F) / static_cast<float>(size) - 0.5F;
      const float v = (static_cast<float>(y) + 0.5F) / static_cast<float>(size) - 0.5F;
      float light = std::exp(-(u * u + v * v) * 6.0F);
      // A soft shadow band, as an object between a light and the surface would cast.
      const float band = std::abs(u + 0.4F * v - 0.1F);
      light *= 0.35F + 0.65F * std::clamp(band * 8.0F, 0.0F, 1.0F);
      std::uint8_t* p = texel(image, x, y);
      p[0] = toByte(light);
      p[1] = toByte(light * 0.95F);
      p[2] = toByte(light * 0.85F);
    }
  }
  return image;
}

}  // namespace lgh
