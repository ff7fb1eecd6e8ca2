#include "gi/albedo_array.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "image/image_common.hpp"

namespace lgh {
namespace {

// Linear -> the nearest sRGB byte (bytes -> linear: image_io::detail::srgbToLinearTable).
std::uint8_t linearToSrgb(float linear) {
  const float c = std::clamp(linear, 0.0F, 1.0F);
  const float encoded = c <= 0.0031308F ? c * 12.92F : 1.055F * std::pow(c, 1.0F / 2.4F) - 0.055F;
  return static_cast<std::uint8_t>(std::lround(encoded * 255.0F));
}

int mipLevels(int size) { return 1 + static_cast<int>(std::floor(std::log2(size))); }

bool usable(const Image8& image) {
  return image.width > 0 && image.height > 0 && image.channels >= 3 &&
         image.pixels.size() >=
             static_cast<std::size_t>(image.width) * image.height * image.channels;
}

}  // namespace

Image8 resampleImage(const Image8& image, int size) {
  Image8 out;
  out.width = size;
  out.height = size;
  out.channels = 4;
  out.pixels.assign(static_cast<std::size_t>(size) * size * 4, 255);
  if (!usable(image)) return out;
  const auto& toLinear = image_io::detail::srgbToLinearTable();
  for (int y = 0; y < size; ++y) {
    const int y0 = y * image.height / size;
    const int y1 = std::max(y0 + 1, (y + 1) * image.height / size);
    for (int x = 0; x < size; ++x) {
      const int x0 = x * image.width / size;
      const int x1 = std::max(x0 + 1, (x + 1) * image.width / size);
      glm::dvec4 sum(0.0);
      for (int sy = y0; sy < y1; ++sy) {
        for (int sx = x0; sx < x1; ++sx) {
          const std::uint8_t* p =
              &image.pixels[(static_cast<std::size_t>(sy) * image.width + sx) * image.channels];
          sum += glm::dvec4(toLinear[p[0]], toLinear[p[1]], toLinear[p[2]],
                            image.channels == 4 ? p[3] / 255.0 : 1.0);
        }
      }
      const glm::dvec4 mean = sum / static_cast<double>((x1 - x0) * (y1 - y0));
      std::uint8_t* q = &out.pixels[(static_cast<std::size_t>(y) * size + x) * 4];
      q[0] = linearToSrgb(static_cast<float>(mean.r));
      q[1] = linearToSrgb(static_cast<float>(mean.g));
      q[2] = linearToSrgb(static_cast<float>(mean.b));
      q[3] = static_cast<std::uint8_t>(std::lround(std::clamp(mean.a, 0.0, 1.0) * 255.0));
    }
  }
  return out;
}

glm::vec3 meanLinearColor(const Image8& image) {
  if (!usable(image)) return glm::vec3(1.0F);
  const auto& toLinear = image_io::detail::srgbToLinearTable();
  glm::dvec3 sum(0.0);
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::uint8_t* p = &image.pixels[i * image.channels];
    sum += glm::dvec3(toLinear[p[0]], toLinear[p[1]], toLinear[p[2]]);
  }
  return glm::vec3(sum / static_cast<double>(pixels));
}

AlbedoArray::AlbedoArray(const Scene& scene, const std::vector<Material>& materials, int maxLayers,
                         std::vector<std::string>& warnings)
    : layerOfImage_(scene.images.size(), -1) {
  std::vector<int> images;
  int skipped = 0;
  for (const Material& material : materials) {
    const int image = material.baseColorTexture.image;
    if (image < 0 || static_cast<std::size_t>(image) >= scene.images.size()) continue;
    if (layerOfImage_[static_cast<std::size_t>(image)] >= 0) continue;
    if (!usable(scene.images[static_cast<std::size_t>(image)])) continue;
    if (static_cast<int>(images.size()) >= maxLayers) {
      ++skipped;
      continue;
    }
    layerOfImage_[static_cast<std::size_t>(image)] = static_cast<int>(images.size());
    images.push_back(image);
  }
  if (skipped > 0) {
    warnings.push_back(fmt::format(
        "gi: {} base-colour textures beyond the {} layers of the albedo array are read as their "
        "material's factor alone",
        skipped, maxLayers));
    spdlog::warn("{}", warnings.back());
  }
  const int layers = std::max(1, static_cast<int>(images.size()));
  glTextureStorage3D(texture_.id(), mipLevels(kAlbedoSize), GL_SRGB8_ALPHA8, kAlbedoSize,
                     kAlbedoSize, layers);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  constexpr std::size_t kLayerBytes = std::size_t{kAlbedoSize} * kAlbedoSize * 4;
  texels_.reserve(kLayerBytes * static_cast<std::size_t>(layers));
  for (std::size_t layer = 0; layer < images.size(); ++layer) {
    const Image8 resized =
        resampleImage(scene.images[static_cast<std::size_t>(images[layer])], kAlbedoSize);
    glTextureSubImage3D(texture_.id(), 0, 0, 0, static_cast<GLint>(layer), kAlbedoSize, kAlbedoSize,
                        1, GL_RGBA, GL_UNSIGNED_BYTE, resized.pixels.data());
    texels_.insert(texels_.end(), resized.pixels.begin(), resized.pixels.end());
  }
  if (images.empty()) {
    const std::array<std::uint8_t, 4> white{255, 255, 255, 255};
    glClearTexImage(texture_.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, white.data());
    texels_.assign(kLayerBytes, 255);
  }
  glGenerateTextureMipmap(texture_.id());
  glSamplerParameteri(sampler_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glSamplerParameteri(sampler_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  // The shader wraps coordinates into [0, 1] by the material's own modes.
  glSamplerParameteri(sampler_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(sampler_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gpuBytes_ = static_cast<std::size_t>(kAlbedoSize) * kAlbedoSize * 4 * 4 / 3 *
              static_cast<std::size_t>(layers);
}

int AlbedoArray::layerOf(int image) const {
  if (image < 0 || static_cast<std::size_t>(image) >= layerOfImage_.size()) return -1;
  return layerOfImage_[static_cast<std::size_t>(image)];
}

}  // namespace lgh
