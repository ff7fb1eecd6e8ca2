// The LGH lighting kernels compiled for the frame's material models and layers only (BrdfFeatures,
// LGH_BRDF_MODELS / LGH_BRDF_LAYERS of glsl/include/brdf.glsl) light every pixel exactly as the
// generic kernel with every model does: on llvmpipe, small. Scenes: the demo with its row of the
// lecture's models and clearcoat, sheen and specular layers on three of its metallic-roughness
// materials (transmission left out), and the demo made plain metallic-roughness. For each, the
// compute path (without and with interleaving) and the raster path, with the brute-force
// reference: the LGH image, the reservoir sums, the shadow samples and the reference must be
// bit-identical between the specialised and the generic kernels. On one llvmpipe thread: the
// hierarchy's builder sums floats with atomics, in an order that varies from run to run on several
// threads, and with it the last bits of the grid lights (so of every frame, whichever kernel).
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "context/gl_context.hpp"
#include "frame_pipeline.hpp"
#include "scene/demo_scene.hpp"
#include "scene/scene_cache.hpp"
#include "test_support.hpp"

namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr int kVpls = 2000;

lgh::Material& named(lgh::Scene& scene, const std::string& name) {
  for (lgh::Material& material : scene.materials) {
    if (material.name == name) return material;
  }
  throw std::runtime_error("no material " + name);
}

lgh::Scene layeredDemo() {
  lgh::Scene scene = lgh::makeDemoScene();
  named(scene, "white").clearcoat.factor = 0.8F;
  named(scene, "white").clearcoat.roughness = 0.2F;
  named(scene, "red").sheen.colorFactor = glm::vec3(0.6F, 0.5F, 0.4F);
  named(scene, "red").sheen.roughnessFactor = 0.4F;
  named(scene, "green").specular.ior = 1.8F;
  return scene;
}

lgh::Scene plainDemo() {
  lgh::Scene scene = lgh::makeDemoScene();
  for (lgh::Material& material : scene.materials) {
    material.model = lgh::MaterialModel::MetallicRoughness;
  }
  return scene;
}

std::shared_ptr<lgh::CachedScene> cache(lgh::Scene scene) {
  auto cached = std::make_shared<lgh::CachedScene>();
  cached->scene = std::move(scene);
  cached->gpu = std::make_unique<lgh::GpuScene>(cached->scene, lgh::GpuSceneOptions{});
  return cached;
}

struct Frame {
  lgh::FrameReport result;
  lgh::LghFrameProbe probe;
};

template <typename T>
std::size_t differing(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  std::size_t count = 0;
  for (std::size_t i = 0; i < a.size(); ++i) count += a[i] == b[i] ? 0 : 1;
  return count;
}

bool anyLight(const lgh::FloatImage& image) {
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    if (image.rgba[i] + image.rgba[i + 1] + image.rgba[i + 2] > 0.0F) return true;
  }
  return false;
}

class LghBrdfSpecialisation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    setenv("LP_NUM_THREADS", "1", 1);
    context = lgh::GlContext::create(lgh::test::rendererOptions());
    pipeline = std::make_unique<lgh::FramePipeline>();
  }
  static void TearDownTestSuite() {
    pipeline.reset();
    context.reset();
  }

  static Frame render(const lgh::CachedScene& scene, const std::string& path,
                      const std::string& interleave, bool generic) {
    const lgh::RenderRequest request = lgh::parseRenderRequest(fmt::format(
        R"({{"output": {{"width": {}, "height": {}}},
            "settings": {{"lgh": {{"enabled": true, "vpl_count": {}, "seed": 3, "alpha": 2,
              "path": "{}", "interleave": "{}"}}}}}})",
        kWidth, kHeight, kVpls, path, interleave));
    Frame frame;
    frame.probe.bruteForce = true;
    frame.probe.genericBrdf = generic;
    lgh::gl::GpuTimer timer;
    pipeline->render(request, scene, timer, frame.result, &frame.probe);
    return frame;
  }

  // Renders `scene` with both kernels on every path and expects identical results.
  static void expectIdentical(const lgh::CachedScene& scene, const std::string& specialisedBrdf) {
    for (const auto& [path, interleave] :
         {std::pair{"compute", "none"}, std::pair{"compute", "2x2"}, std::pair{"raster", "none"}}) {
      const std::string label = fmt::format("{} {} {}", scene.scene.name, path, interleave);
      const Frame specialised = render(scene, path, interleave, false);
      const Frame generic = render(scene, path, interleave, true);
      EXPECT_EQ(specialised.result.decisions.at("lgh_brdf"), specialisedBrdf) << label;
      EXPECT_EQ(generic.result.decisions.at("lgh_brdf"), "all") << label;
      EXPECT_TRUE(anyLight(specialised.probe.indirect)) << label;
      EXPECT_EQ(differing(specialised.probe.indirect.rgba, generic.probe.indirect.rgba), 0U)
          << label;
      EXPECT_EQ(differing(specialised.probe.reference.rgba, generic.probe.reference.rgba), 0U)
          << label;
      EXPECT_EQ(differing(specialised.probe.reservoirSums, generic.probe.reservoirSums), 0U)
          << label;
      EXPECT_EQ(differing(specialised.probe.shadowSamples, generic.probe.shadowSamples), 0U)
          << label;
      EXPECT_EQ(differing(specialised.result.image.rgba, generic.result.image.rgba), 0U) << label;
    }
  }

  static inline std::unique_ptr<lgh::GlContext> context;
  static inline std::unique_ptr<lgh::FramePipeline> pipeline;
};

TEST_F(LghBrdfSpecialisation, ModelsAndLayersSceneLitAsByTheGenericKernel) {
  const auto scene = cache(layeredDemo());
  expectIdentical(*scene,
                  "metallic-roughness,phong,blinn-phong,oren-nayar,cook-torrance "
                  "layers:clearcoat,sheen,specular");
}

TEST_F(LghBrdfSpecialisation, MetallicRoughnessSceneLitAsByTheGenericKernel) {
  const auto scene = cache(plainDemo());
  expectIdentical(*scene, "metallic-roughness layers:none");
}

}  // namespace
