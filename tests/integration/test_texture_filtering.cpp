// Texture filtering at a grazing angle (the lecture's "texture filtering", "mipmapping",
// "anisotropic filtering"): a checkerboard plane seen from 0.25 m above it, to the horizon,
// rendered with each filter of a request's materials[].parameters.sampling on llvmpipe:
//   nearest      nearest texel, no mipmaps: aliasing (moire) in the distance
//   linear       bilinear, no mipmaps: the same, slightly softer
//   trilinear    bilinear within two mip levels, linear between them: no aliasing, but the level
//                follows the footprint's long axis, so the distance blurs to grey
//   anisotropic  trilinear along the footprint's long axis, up to 16 samples: sharper there
//   bicubic      Catmull-Rom in the shader where magnified, trilinear beyond
// Measured per filter, in a band of rows below the horizon where the footprint is long and thin:
// the RMS contrast (standard deviation / mean of luminance), and the relative RMSE against a
// 4 x 4 supersampled anisotropic render (box-filtered: the reference). Checks: anisotropic keeps
// more contrast than trilinear, and is closer to the reference than nearest and trilinear. The
// figures go to docs/MATERIALS.md. With LGH_GALLERY_DIR set, the five renders are written side by
// side as filtering.png (docs/GALLERY.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "context/gl_context.hpp"
#include "frame_pipeline.hpp"
#include "scene/procedural_textures.hpp"
#include "scene/scene_cache.hpp"
#include "test_support.hpp"

namespace {

using json = nlohmann::json;

constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr int kSupersample = 4;
// The band measured: image rows (top first) just below the horizon (row 56), where the checker is
// minified most along the view direction and little across it.
constexpr int kBandTop = 60;
constexpr int kBandBottom = 76;

lgh::Scene checkerPlane() {
  lgh::Scene scene;
  scene.name = "checker_plane";
  scene.images = {lgh::makeCheckerImage(64, 8, 235, 20)};
  lgh::TextureRef texture;
  texture.image = 0;
  scene.textures = {texture};
  lgh::Primitive plane;
  plane.material = 0;
  plane.tangents = true;
  constexpr float kHalf = 20.0F;
  constexpr float kRepeats = 20.0F;  // 8 x 8 tiles per repeat: tiles of 0.25 m
  const glm::vec3 up(0, 1, 0);
  auto corner = [&](float x, float z, float u, float v) {
    lgh::Vertex vertex;
    vertex.position = {x, 0.0F, z};
    vertex.normal = up;
    vertex.tangent = glm::vec4(1, 0, 0, 1);
    vertex.uv0 = {u, v};
    return vertex;
  };
  plane.vertices = {corner(-kHalf, kHalf, 0, kRepeats), corner(kHalf, kHalf, kRepeats, kRepeats),
                    corner(kHalf, -kHalf, kRepeats, 0), corner(-kHalf, -kHalf, 0, 0)};
  plane.indices = {0, 1, 2, 0, 2, 3};
  scene.meshes = {lgh::Mesh{"plane", {plane}, {}}};
  scene.instances = {{0, glm::mat4(1.0F)}};
  lgh::Material material;
  material.name = "checker";
  material.metallicFactor = 0.0F;
  material.roughnessFactor = 1.0F;
  material.baseColorTexture.image = 0;
  scene.materials = {material};
  lgh::LightDesc sun;
  sun.type = lgh::LightType::Directional;
  sun.direction = {0.0F, -1.0F, 0.0F};
  sun.intensity = 3.0F;
  scene.lights = {sun};
  scene.computeBounds();
  return scene;
}

struct Measure {
  double contrast = 0.0;
  double errorVsReference = 0.0;
};

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

double bandContrast(const lgh::FloatImage& image) {
  double sum = 0.0;
  double squares = 0.0;
  int count = 0;
  for (int y = kBandTop; y < kBandBottom; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double l = luminance(image.pixel(x, y));
      sum += l;
      squares += l * l;
      ++count;
    }
  }
  const double mean = sum / count;
  return std::sqrt(std::max(squares / count - mean * mean, 0.0)) / mean;
}

double bandError(const lgh::FloatImage& image, const lgh::FloatImage& reference) {
  double difference = 0.0;
  double total = 0.0;
  for (int y = kBandTop; y < kBandBottom; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double a = luminance(image.pixel(x, y));
      const double r = luminance(reference.pixel(x, y));
      difference += (a - r) * (a - r);
      total += r * r;
    }
  }
  return std::sqrt(difference / total);
}

// Box-filters a supersampled image down by `factor`.
lgh::FloatImage downsample(const lgh::FloatImage& image, int factor) {
  lgh::FloatImage out;
  out.width = image.width / factor;
  out.height = image.height / factor;
  out.rgba.assign(static_cast<std::size_t>(out.width) * out.height * 4, 0.0F);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      float* o = out.pixel(x, y);
      for (int dy = 0; dy < factor; ++dy) {
        for (int dx = 0; dx < factor; ++dx) {
          const float* p = image.pixel(x * factor + dx, y * factor + dy);
          for (int c = 0; c < 4; ++c) o[c] += p[c] / static_cast<float>(factor * factor);
        }
      }
    }
  }
  return out;
}

class TextureFiltering : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context = lgh::GlContext::create(lgh::test::rendererOptions());
    pipeline = std::make_unique<lgh::FramePipeline>();
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &maxAnisotropy);
    plane = std::make_shared<lgh::CachedScene>();
    plane->scene = checkerPlane();
    plane->gpu =
        std::make_unique<lgh::GpuScene>(plane->scene, lgh::GpuSceneOptions{maxAnisotropy, {}});
  }
  static void TearDownTestSuite() {
    plane.reset();
    pipeline.reset();
    context.reset();
  }

  static lgh::FloatImage render(const json& sampling, int scale = 1) {
    const json body = {
        {"camera",
         {{"type", "look_at"}, {"position", {0, 0.25, 0}}, {"target", {0, 0, -6}}, {"yfov", 40}}},
        {"output", {{"width", kWidth * scale}, {"height", kHeight * scale}, {"tone_map", "none"}}},
        {"settings", {{"shadows", "off"}, {"ambient", 0}}},
        {"materials", {{{"match", {{"all", true}}}, {"parameters", {{"sampling", sampling}}}}}}};
    const lgh::RenderRequest request = lgh::parseRenderRequest(body);
    lgh::FrameReport report;
    lgh::gl::GpuTimer timer;
    pipeline->render(request, *plane, timer, report);
    return report.image;
  }

  static inline std::unique_ptr<lgh::GlContext> context;
  static inline std::unique_ptr<lgh::FramePipeline> pipeline;
  static inline std::shared_ptr<lgh::CachedScene> plane;
  static inline float maxAnisotropy = 1.0F;
};

TEST_F(TextureFiltering, AnisotropicIsSharperThanTrilinear) {
  ASSERT_GE(maxAnisotropy, 4.0F) << "the device has no anisotropic filtering to test";
  const double anisotropy = std::min(maxAnisotropy, 16.0F);
  const std::vector<std::pair<std::string, json>> modes = {
      {"nearest", {{"filter", "nearest"}, {"mipmaps", "none"}}},
      {"linear", {{"filter", "linear"}, {"mipmaps", "none"}}},
      {"trilinear", {{"filter", "linear"}, {"mipmaps", "linear"}, {"anisotropy", 1}}},
      {"anisotropic", {{"filter", "linear"}, {"mipmaps", "linear"}, {"anisotropy", anisotropy}}},
      {"bicubic", {{"filter", "bicubic"}, {"mipmaps", "linear"}, {"anisotropy", 1}}},
  };
  const lgh::FloatImage reference = downsample(render(modes[3].second, kSupersample), kSupersample);
  std::map<std::string, Measure> measures;
  std::vector<lgh::FloatImage> images;
  for (const auto& [name, sampling] : modes) {
    images.push_back(render(sampling));
    measures[name] = {bandContrast(images.back()), bandError(images.back(), reference)};
    std::cout << fmt::format("filter {:<12} contrast {:.3f}  relative RMSE vs reference {:.3f}\n",
                             name, measures[name].contrast, measures[name].errorVsReference);
  }
  std::cout << fmt::format("reference (4x4 supersampled anisotropic) contrast {:.3f}\n",
                           bandContrast(reference));
  EXPECT_GT(measures["anisotropic"].contrast, 1.2 * measures["trilinear"].contrast);
  EXPECT_LT(measures["anisotropic"].errorVsReference, measures["trilinear"].errorVsReference);
  EXPECT_LT(measures["anisotropic"].errorVsReference, measures["nearest"].errorVsReference);

  if (const char* directory = std::getenv("LGH_GALLERY_DIR"); directory && *directory != '\0') {
    lgh::Image8 strip;
    strip.channels = 3;
    strip.height = kHeight;
    strip.width = static_cast<int>(images.size()) * (kWidth + 2) - 2;
    strip.pixels.assign(static_cast<std::size_t>(strip.width) * kHeight * 3, 255);
    for (std::size_t i = 0; i < images.size(); ++i) {
      const lgh::Image8 display = lgh::toDisplay8(images[i], lgh::ToneMap::None, 1.0F, false);
      for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
          for (int c = 0; c < 3; ++c) {
            const auto left = static_cast<int>(i) * (kWidth + 2);
            strip.pixels[(static_cast<std::size_t>(y) * strip.width + left + x) * 3 + c] =
                display.pixels[(static_cast<std::size_t>(y) * kWidth + x) * display.channels + c];
          }
        }
      }
    }
    std::filesystem::create_directories(directory);
    lgh::image_io::writeFile(std::filesystem::path(directory) / "filtering.png",
                             lgh::image_io::encodePng(strip));
  }
}

}  // namespace
