// The context paths side by side: EGL device (llvmpipe as Mesa's software device), EGL
// surfaceless and OSMesa all run the same llvmpipe here, so every golden scene must come out with
// the same pixels on each; each result names the path it took. And the GL loader: functions come
// from the current context's own table, and a GL call on a thread without one fails by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "context/gl_context.hpp"
#include "lgh/renderer.hpp"
#include "test_support.hpp"

namespace {

// The requests of test_render_golden.cpp (small sizes).
const std::vector<std::string> kGoldenRequests = {
    R"({"output": {"width": 160, "height": 120}})",
    R"({"camera": {"type": "look_at", "position": [0, 1, 3.4], "target": [0, 0.9, 0], "yfov": 50},
        "output": {"width": 128, "height": 128, "tone_map": "reinhard"}})",
    R"({"scene": {"asset": "BoxTextured-glTF/BoxTextured.gltf"},
        "output": {"width": 128, "height": 96}})",
    R"({"scene": {"asset": "2CylinderEngine-glTF-Binary/2CylinderEngine.glb"},
        "camera": {"type": "auto", "view_direction": [1, 0.5, 1]},
        "output": {"width": 160, "height": 120}})",
    R"({"scene": {"asset": "cameras/Cameras.gltf"}, "camera": {"type": "gltf", "index": 0},
        "output": {"width": 96, "height": 96}})",
};

// An LGH frame sums grid lights with float atomics, whose order varies from run to run on any
// path: equal up to rounding, not bit for bit.
const std::string kLghRequest = R"({"settings": {"lgh": {"enabled": true, "vpl_count": 2000}},
                                    "output": {"width": 96, "height": 72}})";

double largestRelativeDifference(const lgh::FloatImage& a, const lgh::FloatImage& b) {
  double largest = 0.0;
  for (size_t i = 0; i < a.rgba.size(); ++i) {
    const double scale =
        std::max({1e-3, std::fabs(double{a.rgba[i]}), std::fabs(double{b.rgba[i]})});
    largest = std::max(largest, std::fabs(double{a.rgba[i]} - double{b.rgba[i]}) / scale);
  }
  return largest;
}

// The linear pixels of `request` (rendered as exr-float whatever it asks for).
lgh::FloatImage linearImage(lgh::Renderer& renderer, const std::string& json) {
  lgh::RenderRequest request = lgh::parseRenderRequest(json);
  request.output.format = lgh::ImageFormat::ExrFloat;
  return renderer.renderFrame(request).pixels.toFloatImage();
}

std::vector<lgh::FloatImage> renderAll(lgh::ContextBackend backend, std::string& contextPath) {
  lgh::RendererOptions options;
  options.backend = backend;
  options.assetRoot = lgh::test::assimpGltfDir();
  lgh::Renderer renderer(options);
  contextPath = renderer.device().contextPath;
  std::vector<lgh::FloatImage> images;
  for (const std::string& request : kGoldenRequests) {
    images.push_back(linearImage(renderer, request));
  }
  images.push_back(linearImage(renderer, kLghRequest));
  return images;
}

TEST(ContextPaths, EveryPathRendersTheGoldenScenesIdentically) {
  std::string surfacelessPath;
  const auto reference = renderAll(lgh::ContextBackend::Surfaceless, surfacelessPath);
  EXPECT_EQ(surfacelessPath, "surfaceless");
  for (const auto backend : {lgh::ContextBackend::OSMesa, lgh::ContextBackend::EglDevice}) {
    std::string path;
    const auto images = renderAll(backend, path);
    EXPECT_EQ(path, lgh::contextBackendName(backend));
    ASSERT_EQ(images.size(), reference.size());
    for (size_t i = 0; i < kGoldenRequests.size(); ++i) {
      EXPECT_EQ(images[i].width, reference[i].width);
      EXPECT_TRUE(images[i].rgba == reference[i].rgba)
          << path << " differs from surfaceless on request " << i << ": " << kGoldenRequests[i];
    }
    ASSERT_EQ(images.back().rgba.size(), reference.back().rgba.size());
    EXPECT_LT(largestRelativeDifference(images.back(), reference.back()), 1e-3) << path;
  }
}

TEST(ContextPaths, OsmesaReportsItsPathAndGl45) {
  lgh::RendererOptions options;
  options.backend = lgh::ContextBackend::OSMesa;
  lgh::Renderer renderer(options);
  EXPECT_EQ(renderer.device().contextPath, "osmesa");
  EXPECT_GE(renderer.device().glMajor * 10 + renderer.device().glMinor, 45);
  EXPECT_NE(renderer.device().glRenderer.find("llvmpipe"), std::string::npos);
  const lgh::RenderResult result =
      renderer.render(lgh::parseRenderRequest(R"({"output": {"width": 8, "height": 8}})"));
  EXPECT_EQ(result.device.contextPath, "osmesa");
}

// Mesa's EGL gives a robust context with reset notification (through EGL 1.5's attributes, the
// ones NVIDIA's EGL accepts too); OSMesa has no way to ask for one.
TEST(ContextPaths, EglContextsAreRobustOsmesaIsNot) {
  for (const auto backend : {lgh::ContextBackend::Surfaceless, lgh::ContextBackend::OSMesa}) {
    lgh::RendererOptions options;
    options.backend = backend;
    lgh::Renderer renderer(options);
    EXPECT_EQ(renderer.device().robustContext, backend != lgh::ContextBackend::OSMesa)
        << renderer.device().contextPath;
  }
}

TEST(ContextPaths, EachContextOwnsItsFunctionTable) {
  auto surfaceless = lgh::GlContext::create([] {
    lgh::RendererOptions options;
    options.backend = lgh::ContextBackend::Surfaceless;
    return options;
  }());
  EXPECT_EQ(lgh::gl::currentApi(), &surfaceless->api());
  EXPECT_NE(surfaceless->api().DispatchCompute, nullptr);
  // Another thread has no GL functions until a context is made current there.
  std::thread([] { EXPECT_EQ(lgh::gl::currentApi(), nullptr); }).join();
  surfaceless.reset();
  EXPECT_EQ(lgh::gl::currentApi(), nullptr);
}

// Two renderers on one thread, on the same EGL display: each makes its own context current when
// it renders or is destroyed, and destroying one leaves the display to the other.
TEST(ContextPaths, RenderersShareAThreadAndADisplay) {
  const char* request = R"({"output": {"width": 24, "height": 16}})";
  lgh::Renderer first(lgh::test::rendererOptions());
  const lgh::FloatImage reference = linearImage(first, request);
  for (int round = 0; round < 3; ++round) {
    auto second = std::make_unique<lgh::Renderer>(lgh::test::rendererOptions());
    EXPECT_TRUE(linearImage(*second, request).rgba == reference.rgba);
    EXPECT_TRUE(linearImage(first, request).rgba == reference.rgba);
    second.reset();  // while `first`'s context is the current one
    EXPECT_TRUE(linearImage(first, request).rgba == reference.rgba) << "round " << round;
  }
}

// A GPU reset ends a renderer (the test hook reports one after two frames): that frame and every
// later one fail with Unavailable, and a new renderer renders as before.
TEST(ContextPaths, ALostContextEndsTheRendererAndANewOneRenders) {
  // Linear pixels, not file bytes: the files' metadata carry the frame's timings.
  const auto request =
      lgh::parseRenderRequest(R"({"output": {"width": 24, "height": 16, "format": "exr-float"}})");
  const auto pixelsOf = [](const lgh::RenderResult& result) {
    return result.pixels.toFloatImage().rgba;
  };
  std::vector<float> reference;
  {
    lgh::Renderer clean(lgh::test::rendererOptions());
    reference = pixelsOf(clean.render(request));
  }
  setenv("LGH_DEBUG_CONTEXT_LOSS_AFTER", "2", 1);
  {
    lgh::Renderer renderer(lgh::test::rendererOptions());
    unsetenv("LGH_DEBUG_CONTEXT_LOSS_AFTER");
    EXPECT_TRUE(pixelsOf(renderer.render(request)) == reference);
    EXPECT_TRUE(pixelsOf(renderer.render(request)) == reference);
    EXPECT_TRUE(renderer.healthy());
    for (int i = 0; i < 2; ++i) {
      try {
        renderer.render(request);
        FAIL() << "a lost context rendered";
      } catch (const lgh::Error& error) {
        EXPECT_EQ(error.code(), lgh::ErrorCode::Unavailable) << error.what();
      }
      EXPECT_FALSE(renderer.healthy());
    }
  }
  lgh::Renderer again(lgh::test::rendererOptions());
  EXPECT_TRUE(pixelsOf(again.render(request)) == reference);
}

TEST(ContextPathsDeathTest, GlCallWithoutContextNamesTheCall) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(glFinish(), "glFinish called on a thread with no current GL context");
}

}  // namespace
