// Shadows through the whole frame (GL ray setup, the Vulkan tracer on lavapipe, the GL side of its
// buffers, direct lighting, the LGH shadow ratio and its filter), on llvmpipe + lavapipe:
//  - a known occluder casts its shadow where geometry says it must, and nowhere else;
//  - both tracing paths give the same image; shadows only ever darken;
//  - the LGH's shadow samples are traced and filtered; the shadowed brute-force reference;
//  - soft shadows from a light with a radius have penumbrae;
//  - acceleration structures built ahead on a prefetch thread trace as those built when drawn;
//  - without a Vulkan driver: auto renders unshadowed with a warning, "on" fails with 503.
// Golden images of the shadowed demo are in test_render_golden.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "lgh/base64.hpp"
#include "lgh/error.hpp"
#include "lgh/renderer.hpp"
#include "test_support.hpp"

namespace {

using json = nlohmann::json;

class Shadows : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { renderer = std::make_unique<lgh::Renderer>(options()); }
  static void TearDownTestSuite() { renderer.reset(); }

  static lgh::RendererOptions options() {
    lgh::RendererOptions opts = lgh::test::rendererOptions();
    opts.assetRoot = lgh::test::assimpGltfDir();
    return opts;
  }

  // A render and, for the EXR requests of these tests, its linear pixels.
  struct Frame : lgh::RenderResult {
    lgh::FloatImage image;
  };
  static Frame render(const json& request) {
    Frame frame{renderer->render(lgh::parseRenderRequest(request)), {}};
    if (!frame.pixels.isDisplay()) frame.image = frame.pixels.toFloatImage();
    return frame;
  }

  static float luminance(const lgh::FloatImage& image, int x, int y) {
    const float* p = image.pixel(x, y);
    return 0.2126F * p[0] + 0.7152F * p[1] + 0.0722F * p[2];
  }

  static inline std::unique_ptr<lgh::Renderer> renderer;
};

// A ground square (half size 2) at y = 0, an occluder square (half size 0.25) at y = 1, a point
// light at (0, 2, 0) and a camera at (0, 3, 0) looking down (yfov 45 degrees, 128 x 128). The
// occluder's shadow on the ground has half size 0.5: seen from the camera, the occluder covers
// the centre out to 0.30 of the half-width and its shadow reaches 0.40; beyond, the ground is lit.
json occluderRequest(const std::string& shadows) {
  std::vector<lgh::test::Position> positions;
  std::vector<std::uint32_t> indices;
  lgh::test::addSquare(positions, indices, 0.0F, 2.0F);
  lgh::test::addSquare(positions, indices, 1.0F, 0.25F);
  const auto glb = lgh::test::makeTriangleGlb(positions, indices);
  return {{"scene", {{"glb_base64", lgh::base64::encode(glb)}}},
          {"camera",
           {{"type", "look_at"},
            {"position", {0, 3, 0}},
            {"target", {0, 0, 0}},
            {"up", {0, 0, -1}},
            {"yfov", 45}}},
          {"lights", {{{"type", "point"}, {"position", {0, 2, 0}}, {"intensity", 10}}}},
          {"settings", {{"ambient", 0}, {"shadows", shadows}}},
          {"output", {{"width", 128}, {"height", 128}, {"format", "exr-float"}}}};
}

TEST_F(Shadows, AnOccluderShadowsTheGroundWhereGeometrySays) {
  const Frame lit = render(occluderRequest("off"));
  const Frame shadowed = render(occluderRequest("on"));
  EXPECT_EQ(lit.decisions.at("shadows"), "off");
  EXPECT_NE(shadowed.decisions.at("shadows"), "none");
  const auto at = [](float fraction) { return 64 + static_cast<int>(fraction * 64.0F); };
  for (const float fraction : {0.34F, 0.37F}) {  // the ring of shadow around the occluder
    EXPECT_GT(luminance(lit.image, at(fraction), 64), 0.05F) << fraction;
    EXPECT_EQ(luminance(shadowed.image, at(fraction), 64), 0.0F) << fraction;
    EXPECT_EQ(luminance(shadowed.image, 64, at(fraction)), 0.0F) << fraction;
  }
  for (const float fraction : {0.0F, 0.2F, 0.5F, 0.8F}) {  // the occluder's top, the open ground
    EXPECT_FLOAT_EQ(luminance(shadowed.image, at(fraction), 64),
                    luminance(lit.image, at(fraction), 64))
        << fraction;
  }
}

TEST_F(Shadows, BothTracingPathsRenderTheSameImage) {
  json request = {
      {"settings", {{"shadows", "on"}, {"lgh", {{"enabled", true}, {"vpl_count", 3000}}}}},
      {"output", {{"width", 64}, {"height", 48}, {"format", "exr-float"}}}};
  request["settings"]["shadow_path"] = "ray-query";
  const Frame rayQuery = render(request);
  request["settings"]["shadow_path"] = "pipeline";
  const Frame pipeline = render(request);
  EXPECT_EQ(rayQuery.decisions.at("shadows"), "ray-query");
  EXPECT_EQ(pipeline.decisions.at("shadows"), "pipeline");
  // The rays go through lavapipe's memory pinned into GL (shadows/batch_transport.hpp): llvmpipe
  // cannot import lavapipe's memory, so interop is tried, refused and logged first.
  EXPECT_EQ(rayQuery.decisions.at("shadow_transport"), "pinned");
  EXPECT_EQ(pipeline.decisions.at("shadow_transport"), "pinned");
  // The LGH's float atomics vary in the last bits from run to run (test_context_paths.cpp).
  ASSERT_EQ(rayQuery.image.rgba.size(), pipeline.image.rgba.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < rayQuery.image.rgba.size(); ++i) {
    const double a = rayQuery.image.rgba[i];
    const double b = pipeline.image.rgba[i];
    largest = std::max(largest, std::fabs(a - b) / std::max({1e-3, std::fabs(a), std::fabs(b)}));
  }
  EXPECT_LT(largest, 1e-3);
}

TEST_F(Shadows, ShadowsOnlyDarkenTheDemo) {
  json request = {{"output", {{"width", 96}, {"height", 72}, {"format", "exr-float"}}}};
  request["settings"]["shadows"] = "off";
  const Frame off = render(request);
  request["settings"]["shadows"] = "auto";
  const Frame on = render(request);
  int darker = 0;
  for (int y = 0; y < 72; ++y) {
    for (int x = 0; x < 96; ++x) {
      const float a = luminance(off.image, x, y);
      const float b = luminance(on.image, x, y);
      EXPECT_LE(b, a * 1.0001F + 1e-6F) << x << "," << y;
      if (b < 0.9F * a) ++darker;
    }
  }
  EXPECT_GT(darker, 96 * 72 / 50) << "the demo's boxes and sphere cast shadows";
  for (const char* row : {"shadow ray setup", "shadow rays", "shadow transfer"}) {
    EXPECT_GE(on.timings.get(row), 0.0) << row;
  }
  EXPECT_EQ(on.decisions.at("shadow_rays"), "3");  // the demo's three lights, one ray each
  EXPECT_FALSE(on.decisions.at("shadow_transport").empty());
  EXPECT_TRUE(on.warnings.empty());
}

TEST_F(Shadows, LghSamplesAreTracedAndFiltered) {
  json request = {{"settings", {{"lgh", {{"enabled", true}, {"vpl_count", 4000}}}}},
                  {"output", {{"width", 80}, {"height", 60}, {"format", "exr-float"}}}};
  request["settings"]["shadows"] = "off";
  const Frame unshadowed = render(request);
  request["settings"]["shadows"] = "on";
  const Frame shadowed = render(request);
  EXPECT_EQ(shadowed.decisions.at("shadow_rays"), "7");  // 3 direct lights + k = 4 samples
  EXPECT_GE(shadowed.timings.get("shadow filter"), 0.0);
  double sumOff = 0.0;
  double sumOn = 0.0;
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 80; ++x) {
      sumOff += luminance(unshadowed.image, x, y);
      sumOn += luminance(shadowed.image, x, y);
    }
  }
  EXPECT_LT(sumOn, 0.97 * sumOff) << "indirect light is shadowed too";
}

TEST_F(Shadows, ALightWithARadiusCastsPenumbrae) {
  json hard = occluderRequest("on");
  json soft = hard;
  soft["lights"][0]["radius"] = 0.3;
  soft["settings"]["shadow_light_samples"] = 16;
  const Frame hardImage = render(hard);
  const Frame softImage = render(soft);
  EXPECT_EQ(softImage.decisions.at("shadow_rays"), "16");
  const Frame open = render(occluderRequest("off"));
  int partial = 0;
  for (int x = 64; x < 128; ++x) {
    const float lit = luminance(open.image, x, 64);
    const float value = luminance(softImage.image, x, 64);
    if (lit > 0.0F && value > 0.1F * lit && value < 0.9F * lit) ++partial;
  }
  EXPECT_GE(partial, 3) << "a penumbra several pixels wide";
  EXPECT_EQ(luminance(hardImage.image, 64 + static_cast<int>(0.37F * 64.0F), 64), 0.0F);
}

TEST_F(Shadows, LightsBeyondTheRayBudgetAreNamedInAWarning) {
  json request = occluderRequest("on");
  request["settings"]["shadow_light_samples"] = 16;
  json light = request["lights"][0];
  for (int i = 0; i < 4; ++i) request["lights"].push_back(light);  // 5 lights x 16 = 80 > 64
  const Frame result = render(request);
  EXPECT_EQ(result.decisions.at("shadow_rays"), "64");
  ASSERT_EQ(result.warnings.size(), 1U);
  EXPECT_NE(result.warnings[0].find("1 of 5 lights cast no shadows"), std::string::npos)
      << result.warnings[0];
}

// The scene cache's look-ahead builds a scene's acceleration structures on its prefetch thread
// (SceneCache::prefetch with ShadowDevice::prefetchBuilder), while the render thread draws: the
// frame then builds nothing, and its shadows are those of a build on the render thread.
TEST_F(Shadows, StructuresBuiltAheadTraceAsThoseBuiltWhenDrawn) {
  const lgh::RenderRequest occluder = lgh::parseRenderRequest(occluderRequest("on"));
  const auto firstShadowedFrame = [] {  // the tracer is made by the first frame that traces
    return lgh::parseRenderRequest(
        R"({"settings": {"shadows": "on"}, "output": {"width": 32, "height": 24}})");
  };
  lgh::Renderer drawn(options());
  drawn.render(firstShadowedFrame());
  const lgh::RenderResult builtWhenDrawn = drawn.render(occluder);
  lgh::Renderer ahead(options());
  ahead.render(firstShadowedFrame());
  ahead.prefetch(occluder);
  const lgh::RenderResult builtAhead = ahead.render(occluder);

  EXPECT_GE(builtWhenDrawn.timings.get("shadow as build wall"), 0.0);
  EXPECT_LT(builtAhead.timings.get("shadow as build wall"), 0.0) << "built again when drawn";
  EXPECT_EQ(builtAhead.decisions.at("scene_parse"), "prefetched");
  EXPECT_EQ(builtAhead.decisions.at("shadows"), builtWhenDrawn.decisions.at("shadows"));
  const lgh::FloatImage a = builtWhenDrawn.pixels.toFloatImage();
  const lgh::FloatImage b = builtAhead.pixels.toFloatImage();
  EXPECT_EQ(a.rgba, b.rgba);
}

// The hand-over modes where GL cannot import Vulkan's memory (shadows/batch_transport.hpp):
// lavapipe's memory pinned into GL, and the staging copies that LGH_NO_PINNED_MEMORY asks for (as
// a driver without GL_AMD_pinned_memory gets them) give the same image, with the occluder's
// shadow in it. Each test runs in a process of its own (ctest): the variable stays here.
TEST_F(Shadows, PinnedAndStagingHandOversGiveTheSameImage) {
  const lgh::RenderRequest occluder = lgh::parseRenderRequest(occluderRequest("on"));
  lgh::Renderer pinned(options());
  const lgh::RenderResult a = pinned.render(occluder);
  setenv("LGH_NO_PINNED_MEMORY", "1", 1);
  lgh::Renderer staging(options());
  const lgh::RenderResult b = staging.render(occluder);
  unsetenv("LGH_NO_PINNED_MEMORY");
  EXPECT_EQ(a.decisions.at("shadow_transport"), "pinned");
  EXPECT_EQ(b.decisions.at("shadow_transport"), "staging");
  const lgh::FloatImage imageA = a.pixels.toFloatImage();
  const lgh::FloatImage imageB = b.pixels.toFloatImage();
  EXPECT_EQ(imageA.rgba, imageB.rgba);
  EXPECT_EQ(luminance(imageA, 64 + static_cast<int>(0.37F * 64.0F), 64), 0.0F) << "shadowed";
  EXPECT_GT(luminance(imageA, 64 + static_cast<int>(0.45F * 64.0F), 64), 0.0F) << "lit";
}

// Each test runs in a process of its own (ctest): the Vulkan loader here finds no driver.
class WithoutVulkan : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("VK_DRIVER_FILES", "/nonexistent/icd.json", 1);
    setenv("VK_ICD_FILENAMES", "/nonexistent/icd.json", 1);
    renderer = std::make_unique<lgh::Renderer>(lgh::test::rendererOptions());
  }
  std::unique_ptr<lgh::Renderer> renderer;
};

TEST_F(WithoutVulkan, AutoRendersUnshadowedAndSaysWhy) {
  const lgh::RenderResult result =
      renderer->render(lgh::parseRenderRequest(R"({"output": {"width": 32, "height": 24}})"));
  EXPECT_EQ(result.decisions.at("shadows"), "none");
  ASSERT_EQ(result.warnings.size(), 1U);
  EXPECT_NE(result.warnings[0].find("rendered without shadows"), std::string::npos);
}

TEST_F(WithoutVulkan, OnIsUnavailableNamingTheField) {
  try {
    renderer->render(lgh::parseRenderRequest(
        R"({"settings": {"shadows": "on"}, "output": {"width": 32, "height": 24}})"));
    FAIL() << "shadows \"on\" rendered without a Vulkan driver";
  } catch (const lgh::Error& error) {
    EXPECT_EQ(error.code(), lgh::ErrorCode::Unavailable);
    EXPECT_EQ(error.field(), "/settings/shadows");
  }
  // The renderer keeps working.
  const lgh::RenderResult after = renderer->render(lgh::parseRenderRequest(
      R"({"settings": {"shadows": "off"}, "output": {"width": 32, "height": 24}})"));
  EXPECT_EQ(after.decisions.at("shadows"), "off");
}

}  // namespace
