// Golden images: the demo scene and glTF assets from Debian's assimp-testmodels rendered small on
// Mesa llvmpipe and compared with committed baselines (tests/golden/). Metric and thresholds:
// see lgh::test::checkGolden. A shading change beyond rounding fails these tests.
#include <gtest/gtest.h>

#include <memory>

#include "lgh/renderer.hpp"
#include "test_support.hpp"

namespace {

// Thresholds: llvmpipe is deterministic on one machine, but LLVM versions and CPU features may
// round differently; 0.5 mean (of 255) and 0.2% of pixels off by more than 16 absorb that while a
// changed BRDF, light or texture moves far more (see docs/TESTING.md).
constexpr double kMaxMeanError = 0.5;
constexpr double kMaxFraction = 0.002;

class GoldenRender : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    lgh::RendererOptions options = lgh::test::rendererOptions();
    options.assetRoot = lgh::test::assimpGltfDir();
    renderer = std::make_unique<lgh::Renderer>(options);
  }
  static void TearDownTestSuite() { renderer.reset(); }

  static lgh::Image8 render(const std::string& requestJson) {
    lgh::RenderRequest request = lgh::parseRenderRequest(requestJson);
    return renderer->render(request).pixels.toImage8();
  }

  static inline std::unique_ptr<lgh::Renderer> renderer;
};

TEST_F(GoldenRender, DemoScene) {
  auto image = render(R"({"output": {"width": 160, "height": 120}})");
  EXPECT_EQ(lgh::test::checkGolden(image, "demo_160x120", kMaxMeanError, kMaxFraction), "");
}

// Global illumination (docs/GI.md): the demo with one bounce of light-traced VPLs through the LGH,
// shadowed (direct light and the LGH's sampled, filtered shadows).
TEST_F(GoldenRender, DemoSceneWithOneBounce) {
  auto image = render(R"({"output": {"width": 160, "height": 120},
                         "settings": {"shadows": "on",
                                      "gi": {"enabled": true, "bounces": 1, "vpl_count": 20000}}})");
  EXPECT_EQ(lgh::test::checkGolden(image, "demo_gi_1bounce_160x120", kMaxMeanError, kMaxFraction),
            "");
}

TEST_F(GoldenRender, DemoSceneLookAt) {
  auto image = render(R"({"camera": {"type": "look_at", "position": [0, 1, 3.4],
                         "target": [0, 0.9, 0], "yfov": 50},
                         "output": {"width": 128, "height": 128, "tone_map": "reinhard"}})");
  EXPECT_EQ(lgh::test::checkGolden(image, "demo_lookat_128", kMaxMeanError, kMaxFraction), "");
}

TEST_F(GoldenRender, BoxTexturedGltf) {
  auto image = render(R"({"scene": {"asset": "BoxTextured-glTF/BoxTextured.gltf"},
                         "output": {"width": 128, "height": 96}})");
  EXPECT_EQ(lgh::test::checkGolden(image, "box_textured_128x96", kMaxMeanError, kMaxFraction), "");
}

// The G-buffer pass leaves the emissive and layers targets unwritten in frames whose surfaces need
// neither (passes/gbuffer_pass.hpp). A plain frame right after an unlit one (all emission) and a
// Phong one (classic parameters in the layers target), same asset and size, so that every pixel
// still holds the earlier frames' values, must be the plain golden image.
TEST_F(GoldenRender, APlainFrameReadsNothingLeftByTheFramesBefore) {
  const std::string box = R"("scene": {"asset": "BoxTextured-glTF/BoxTextured.gltf"},
                             "output": {"width": 128, "height": 96})";
  for (const char* model : {"unlit", "phong"}) {
    render("{" + box + R"(, "materials": [{"match": {"all": true},
                                           "parameters": {"model": ")" +
           model + R"("}}]})");
  }
  EXPECT_EQ(lgh::test::checkGolden(render("{" + box + "}"), "box_textured_128x96", kMaxMeanError,
                                   kMaxFraction),
            "");
}

TEST_F(GoldenRender, CylinderEngineGlb) {
  auto image = render(R"({"scene": {"asset": "2CylinderEngine-glTF-Binary/2CylinderEngine.glb"},
                         "camera": {"type": "auto", "view_direction": [1, 0.5, 1]},
                         "output": {"width": 160, "height": 120}})");
  EXPECT_EQ(lgh::test::checkGolden(image, "engine_160x120", kMaxMeanError, kMaxFraction), "");
}

TEST_F(GoldenRender, GltfCamera) {
  auto image = render(R"({"scene": {"asset": "cameras/Cameras.gltf"},
                         "camera": {"type": "gltf", "index": 0},
                         "output": {"width": 96, "height": 96}})");
  EXPECT_EQ(lgh::test::checkGolden(image, "cameras_gltf0_96", kMaxMeanError, kMaxFraction), "");
}

TEST_F(GoldenRender, TransparentBackgroundKeepsAlpha) {
  lgh::RenderRequest request = lgh::parseRenderRequest(
      R"({"scene": {"asset": "BoxTextured-glTF/BoxTextured.gltf"},
          "output": {"width": 64, "height": 64, "transparent_background": true}})");
  const lgh::Image8 image = renderer->render(request).pixels.toImage8();
  ASSERT_EQ(image.channels, 4);
  EXPECT_EQ(image.pixels[3], 0);                         // the corner: background
  EXPECT_EQ(image.pixels[(32 * 64 + 32) * 4 + 3], 255);  // the centre: the box
}

TEST_F(GoldenRender, TimingTableHasEveryPass) {
  lgh::RenderResult result =
      renderer->render(lgh::parseRenderRequest(R"({"output": {"width": 32, "height": 32}})"));
  for (const char* pass :
       {"gbuffer", "direct lighting", "scene load", "upload", "readback", "encode", "total"}) {
    EXPECT_GE(result.timings.get(pass), 0.0) << pass;
  }
  // The demo's default frame is lit by its direct lights alone: the direct lighting pass writes
  // the output, and no composite runs (test_lgh_lighting times the composite of LGH frames).
  EXPECT_EQ(result.decisions.at("lighting"), "direct");
  EXPECT_LT(result.timings.get("composite"), 0.0);
  EXPECT_FALSE(result.device.glRenderer.empty());
  EXPECT_FALSE(result.device.contextPath.empty());
}

TEST_F(GoldenRender, SecondRenderOfSameSceneHitsCache) {
  const char* request = R"({"scene": {"asset": "BoxTextured-glTF/BoxTextured.gltf"},
                            "output": {"width": 16, "height": 16}})";
  renderer->render(lgh::parseRenderRequest(request));
  lgh::RenderResult second = renderer->render(lgh::parseRenderRequest(request));
  EXPECT_TRUE(second.sceneCacheHit);
  EXPECT_EQ(second.decisions.at("scene_cache"), "hit");
}

TEST_F(GoldenRender, BadAssetIsAnErrorAndRendererStaysUsable) {
  EXPECT_THROW(renderer->render(lgh::parseRenderRequest(
                   R"({"scene": {"asset": "IndexOutOfRange/IndexOutOfRange.gltf"}})")),
               lgh::Error);
  EXPECT_THROW(
      renderer->render(lgh::parseRenderRequest(R"({"scene": {"asset": "../etc/passwd"}})")),
      lgh::Error);
  auto image = render(R"({"output": {"width": 160, "height": 120}})");
  EXPECT_EQ(lgh::test::checkGolden(image, "demo_160x120", kMaxMeanError, kMaxFraction), "");
}

}  // namespace
