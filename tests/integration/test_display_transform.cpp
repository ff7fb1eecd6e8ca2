// The display transform on the GPU (glsl/include/display_transform.glsl, in the composite pass)
// against the CPU's lgh::toDisplay8, the exact reference:
//  - at chosen values: every sRGB rounding threshold and its float neighbours, NaN, infinities,
//    negatives, huge values; every tone map and a few exposures; alpha at every code's edges;
//  - on the golden scenes: the PNG frame (display codes from the GPU) against the same frame read
//    back as linear floats and converted on the CPU.
// Both count the same thresholds, so a channel may differ only where float arithmetic on the two
// sides lands a value across one threshold: by one step at most. Without a tone map at exposure 1
// nothing is computed before the count, so the codes must be equal.
// The pixel pack pass's two shapes (the shader's, the GPUs', and the driver's copy, the CPU
// rasterizers') give the same bytes, those of the output target's rows with or without alpha, at
// sizes whose bytes end inside a word, RGB and RGBA.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "context/gl_context.hpp"
#include "gl/gl_objects.hpp"
#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "image/image_common.hpp"
#include "lgh/renderer.hpp"
#include "passes/pixel_pack_pass.hpp"
#include "test_support.hpp"

namespace {

class DisplayTransform : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    lgh::RendererOptions options = lgh::test::rendererOptions();
    options.assetRoot = lgh::test::assimpGltfDir();
    renderer = std::make_unique<lgh::Renderer>(options);
  }
  static void TearDownTestSuite() { renderer.reset(); }

  // The kernel's codes for `values` (a colour channel, or alpha).
  static std::vector<std::uint32_t> gpuCodes(const std::vector<float>& values, lgh::ToneMap toneMap,
                                             float exposure, bool alpha) {
    const lgh::gl::Program program = lgh::gl::buildComputeProgram("display_transform_check.comp");
    const GLuint id = program.id();
    const auto& thresholds = lgh::image_io::detail::srgbThresholds();
    glProgramUniform1fv(id, glGetUniformLocation(id, "uSrgbThresholds"), 255, thresholds.data());
    glProgramUniform1i(id, glGetUniformLocation(id, "uToneMap"), static_cast<int>(toneMap));
    glProgramUniform1f(id, glGetUniformLocation(id, "uExposure"), exposure);
    glProgramUniform1ui(id, glGetUniformLocation(id, "uCount"), static_cast<GLuint>(values.size()));
    glProgramUniform1i(id, glGetUniformLocation(id, "uAlpha"), alpha ? 1 : 0);
    lgh::gl::Buffer input;
    lgh::gl::Buffer output;
    glNamedBufferStorage(input.id(), static_cast<GLsizeiptr>(values.size() * sizeof(float)),
                         values.data(), 0);
    glNamedBufferStorage(output.id(), static_cast<GLsizeiptr>(values.size() * 4), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, input.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, output.id());
    glUseProgram(id);
    glDispatchCompute(static_cast<GLuint>((values.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> codes(values.size());
    glGetNamedBufferSubData(output.id(), 0, static_cast<GLsizeiptr>(codes.size() * 4),
                            codes.data());
    return codes;
  }

  // toDisplay8's codes for `values`, as red (or alpha) of a one-row image.
  static std::vector<std::uint32_t> cpuCodes(const std::vector<float>& values, lgh::ToneMap toneMap,
                                             float exposure, bool alpha) {
    lgh::FloatImage image;
    image.width = static_cast<int>(values.size());
    image.height = 1;
    image.rgba.assign(values.size() * 4, 0.0F);
    for (std::size_t i = 0; i < values.size(); ++i) image.rgba[i * 4 + (alpha ? 3 : 0)] = values[i];
    const lgh::Image8 display = lgh::toDisplay8(image, toneMap, exposure, true);
    std::vector<std::uint32_t> codes(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
      codes[i] = display.pixels[i * 4 + (alpha ? 3 : 0)];
    return codes;
  }

  static inline std::unique_ptr<lgh::Renderer> renderer;
};

// Every threshold with its float neighbours, special values, and random values over [0, 8].
std::vector<float> probeValues() {
  std::vector<float> values = {0.0F,
                               -0.0F,
                               -1.0F,
                               1.0F,
                               1.5F,
                               1e6F,
                               1e7F,
                               std::numeric_limits<float>::infinity(),
                               -std::numeric_limits<float>::infinity(),
                               std::numeric_limits<float>::quiet_NaN(),
                               std::numeric_limits<float>::denorm_min()};
  const auto& thresholds = lgh::image_io::detail::srgbThresholds();
  for (int k = 0; k < 255; ++k) {
    const float t = thresholds[k];
    values.push_back(std::nextafter(t, 0.0F));
    values.push_back(t);
    values.push_back(std::nextafter(t, 2.0F));
  }
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(0.0F, 8.0F);
  for (int i = 0; i < 20000; ++i) values.push_back(uniform(random));
  return values;
}

TEST_F(DisplayTransform, KernelEqualsTheCpuWithoutToneMap) {
  const std::vector<float> values = probeValues();
  const auto gpu = gpuCodes(values, lgh::ToneMap::None, 1.0F, false);
  const auto cpu = cpuCodes(values, lgh::ToneMap::None, 1.0F, false);
  for (std::size_t i = 0; i < values.size(); ++i) {
    ASSERT_EQ(gpu[i], cpu[i]) << fmt::format("value {:.9g}", values[i]);
  }
}

TEST_F(DisplayTransform, KernelIsWithinOneStepOfTheCpuForEveryToneMapAndExposure) {
  const std::vector<float> values = probeValues();
  for (const lgh::ToneMap toneMap :
       {lgh::ToneMap::None, lgh::ToneMap::Reinhard, lgh::ToneMap::Aces}) {
    for (const float exposure : {0.5F, 1.0F, 2.7F}) {
      const auto gpu = gpuCodes(values, toneMap, exposure, false);
      const auto cpu = cpuCodes(values, toneMap, exposure, false);
      std::size_t differing = 0;
      for (std::size_t i = 0; i < values.size(); ++i) {
        const int difference = static_cast<int>(gpu[i]) - static_cast<int>(cpu[i]);
        ASSERT_LE(std::abs(difference), 1) << fmt::format(
            "value {:.9g}, tone map {}, exposure {}", values[i], lgh::enumName(toneMap), exposure);
        differing += difference != 0 ? 1 : 0;
      }
      // Off-by-one codes only where a value sits on a threshold's edge: a handful at most.
      EXPECT_LT(differing, values.size() / 100)
          << lgh::enumName(toneMap) << " at exposure " << exposure;
    }
  }
}

TEST_F(DisplayTransform, KernelRoundsAlphaAsTheCpu) {
  std::vector<float> values = {-1.0F, 0.0F, 1.0F, 2.0F, std::numeric_limits<float>::quiet_NaN()};
  for (int code = 0; code <= 255; ++code) {
    const float edge = (static_cast<float>(code) + 0.5F) / 255.0F;
    values.push_back(std::nextafter(edge, 0.0F));
    values.push_back(std::nextafter(edge, 2.0F));
    values.push_back(static_cast<float>(code) / 255.0F);
  }
  const auto gpu = gpuCodes(values, lgh::ToneMap::None, 1.0F, true);
  const auto cpu = cpuCodes(values, lgh::ToneMap::None, 1.0F, true);
  for (std::size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(gpu[i], cpu[i]) << fmt::format("alpha {:.9g}", values[i]);
  }
}

// The golden scenes (tests/integration/test_render_golden.cpp), the transparent background, a
// bright, exposed ACES frame, odd sizes and a frame with blended surfaces.
const std::vector<std::string> kScenes = {
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
    R"({"scene": {"asset": "BoxTextured-glTF/BoxTextured.gltf"},
        "output": {"width": 64, "height": 48, "transparent_background": true}})",
    R"({"output": {"width": 96, "height": 64, "tone_map": "none", "exposure": 3.5}})",
    // Odd sizes: 37 x 19 x 3 bytes end in the middle of the pixel pack pass's last word.
    R"({"output": {"width": 37, "height": 19}})",
    R"({"output": {"width": 13, "height": 7, "transparent_background": true}})",
    // Blended surfaces (the Partial_Coating cell): composited in linear light, blended, then the
    // display pass writes the output (passes/display_pass.hpp).
    R"({"scene": {"asset": "ClearCoat-glTF/ClearCoatTest.gltf"},
        "output": {"width": 96, "height": 96, "transparent_background": true}})",
};

TEST_F(DisplayTransform, PngFramesMatchTheCpuTransformOfTheLinearFrame) {
  for (const std::string& json : kScenes) {
    const lgh::RenderRequest png = lgh::parseRenderRequest(json);
    lgh::RenderRequest exr = png;
    exr.output.format = lgh::ImageFormat::ExrFloat;
    const lgh::Image8 gpu = renderer->renderFrame(png).pixels.toImage8();
    const lgh::Image8 cpu =
        lgh::toDisplay8(renderer->renderFrame(exr).pixels.toFloatImage(), png.output.toneMap,
                        png.output.exposure, png.output.transparentBackground);
    ASSERT_EQ(gpu.channels, cpu.channels) << json;
    ASSERT_EQ(gpu.pixels.size(), cpu.pixels.size()) << json;
    std::size_t differing = 0;
    int largest = 0;
    for (std::size_t i = 0; i < gpu.pixels.size(); ++i) {
      const int difference = std::abs(int{gpu.pixels[i]} - int{cpu.pixels[i]});
      largest = std::max(largest, difference);
      differing += difference != 0 ? 1 : 0;
    }
    EXPECT_LE(largest, 1) << json;
    EXPECT_LT(differing, gpu.pixels.size() / 100) << json;
  }
}

// The background's codes come from the CPU's display transform of the background colour (the
// pixels of a SIMD group that is all background skip the per-pixel transform,
// include/skip_background.glsl): every background pixel, in groups of background alone and beside
// the surfaces, holds exactly toDisplay8 of the colour, for each tone map, exposures, a colour on
// an sRGB threshold, and the transparent background. Odd sizes leave part-filled groups at the
// edges; the demo lit by the LGH writes its output in the composite pass, the others in the
// direct lighting, and the background is found by the other of the two (a skip path that wrote
// anything else shows: both were checked by breaking them).
TEST_F(DisplayTransform, BackgroundPixelsHoldTheCpuCodesOfTheBackgroundColour) {
  const float onThreshold = lgh::image_io::detail::srgbThresholds()[100];
  const std::vector<std::string> requests = {
      R"({"scene": {"asset": "BoxTextured-glTF/BoxTextured.gltf"},
          "output": {"width": 45, "height": 27}})",
      R"({"scene": {"asset": "BoxTextured-glTF/BoxTextured.gltf"},
          "output": {"width": 37, "height": 29, "tone_map": "reinhard", "exposure": 0.7,
                     "background": [3.0, 0.5, 0.0007]}})",
      fmt::format(R"({{"scene": {{"asset": "BoxTextured-glTF/BoxTextured.gltf"}},
          "output": {{"width": 40, "height": 40, "tone_map": "none",
                     "background": [{0:.9g}, {0:.9g}, {0:.9g}]}}}})",
                  onThreshold),
      R"({"scene": {"asset": "BoxTextured-glTF/BoxTextured.gltf"},
          "output": {"width": 33, "height": 17, "transparent_background": true,
                     "background": [0.4, 0.2, 0.1]}})",
      R"({"settings": {"lgh": {"enabled": true, "vpl_count": 3000}},
          "output": {"width": 48, "height": 40, "exposure": 2.0}})",
  };
  for (const std::string& json : requests) {
    const lgh::RenderRequest png = lgh::parseRenderRequest(json);
    // Where the background is, from the other pass: the same view as an EXR with a transparent
    // background (alpha 0 there), written by the composite where the PNG's direct lighting wrote
    // the output, and the other way round.
    lgh::RenderRequest mask = png;
    mask.output.format = lgh::ImageFormat::ExrFloat;
    mask.output.transparentBackground = true;
    mask.settings.lgh.enabled = !png.settings.lgh.enabled;
    mask.settings.lgh.vplCount = std::max(mask.settings.lgh.vplCount, 100);
    const lgh::Image8 display = renderer->renderFrame(png).pixels.toImage8();
    const lgh::FloatImage coverage = renderer->renderFrame(mask).pixels.toFloatImage();
    const float alpha = png.output.transparentBackground ? 0.0F : 1.0F;
    const auto& bg = png.output.background;
    const lgh::FloatImage background{1, 1, {bg[0] * alpha, bg[1] * alpha, bg[2] * alpha, alpha}};
    const lgh::Image8 codes =
        lgh::toDisplay8(background, png.output.toneMap, png.output.exposure, true);
    const auto channels = static_cast<std::size_t>(display.channels);
    const auto pixelCount = static_cast<std::size_t>(coverage.width) * coverage.height;
    std::size_t backgroundPixels = 0;
    for (std::size_t i = 0; i < pixelCount; ++i) {
      if (coverage.rgba[i * 4 + 3] != 0.0F) continue;
      ++backgroundPixels;
      for (std::size_t c = 0; c < channels; ++c) {
        ASSERT_EQ(display.pixels[i * channels + c], codes.pixels[c])
            << json << " pixel " << i << " channel " << c;
      }
    }
    EXPECT_GT(backgroundPixels, pixelCount / 10) << json;
    EXPECT_LT(backgroundPixels, pixelCount) << json;
  }
}

// The rows come out top first, turned over by the composite pass, in every layout: a box seen
// from below its top fills the bottom of the frame and leaves the top row to the (transparent)
// background. A half-float EXR frame agrees with the float one to half precision.
TEST_F(DisplayTransform, EveryOutputLayoutReadsBackTopRowFirst) {
  lgh::RenderRequest request = lgh::parseRenderRequest(
      R"({"scene": {"asset": "BoxTextured-glTF/BoxTextured.gltf"},
          "camera": {"type": "look_at", "position": [0, 0, 2], "target": [0, 0.5, 0]},
          "output": {"width": 32, "height": 32, "transparent_background": true}})");
  const lgh::Image8 display = renderer->renderFrame(request).pixels.toImage8();
  request.output.format = lgh::ImageFormat::ExrHalf;
  const lgh::FloatImage half = renderer->renderFrame(request).pixels.toFloatImage();
  request.output.format = lgh::ImageFormat::ExrFloat;
  const lgh::FloatImage full = renderer->renderFrame(request).pixels.toFloatImage();
  EXPECT_EQ(display.pixels[3], 0) << "top-left alpha";
  EXPECT_EQ(full.rgba[3], 0.0F);
  EXPECT_EQ(display.pixels[(31 * 32 + 16) * 4 + 3], 255) << "bottom-centre alpha";
  EXPECT_EQ(full.pixel(16, 31)[3], 1.0F);
  for (std::size_t i = 0; i < full.rgba.size(); ++i) {
    EXPECT_NEAR(half.rgba[i], full.rgba[i], std::fabs(full.rgba[i]) / 1024.0F + 1e-7F) << i;
  }
}

// The pixel pack pass's work groups cover every invocation (a word each) in rows
// within GL's group count limit: one group more than the guaranteed 65,535 takes two rows.
TEST(PixelPackDispatch, CoversEveryInvocationInRowsWithinTheLimit) {
  constexpr unsigned kLimit = 65535;
  constexpr std::size_t kGroup = LGH_PACK_GROUP;
  for (const std::size_t invocations :
       {std::size_t{1}, kGroup, kGroup + 1, kGroup * kLimit, kGroup * kLimit + 1,
        std::size_t{4096} * 4096, std::size_t{16384} * 16384 / 4}) {
    const lgh::PixelPackPass::Dispatch groups =
        lgh::PixelPackPass::dispatchFor(invocations, kLimit);
    EXPECT_LE(groups.x, kLimit) << invocations;
    EXPECT_GE(std::size_t{groups.x} * groups.y * kGroup, invocations) << invocations;
    EXPECT_LT(std::size_t{groups.x} * (groups.y - 1) * kGroup, invocations) << "a row of nothing";
  }
  EXPECT_EQ(lgh::PixelPackPass::dispatchFor(kGroup * kLimit + 1, kLimit).y, 2U);
  EXPECT_EQ(lgh::PixelPackPass::dispatchFor(0, kLimit).x, 0U);
}

// The bytes each pack shape writes for an output target of random codes.
std::vector<std::uint8_t> packed(lgh::PackShape shape, const lgh::FrameTargets& targets,
                                 lgh::FramePixels::Layout layout) {
  const lgh::FramePixels frame{targets.width, targets.height, layout, nullptr};
  lgh::gl::Buffer buffer;
  const std::vector<std::uint8_t> marks(lgh::PixelPackPass::bufferBytes(frame), 0xA5);
  glNamedBufferStorage(buffer.id(), static_cast<GLsizeiptr>(marks.size()), marks.data(), 0);
  lgh::PixelPackPass pass(shape);
  pass.run(targets, lgh::OutputPixels::Display8, layout, buffer.id());
  glFinish();
  std::vector<std::uint8_t> bytes(frame.size());
  glGetNamedBufferSubData(buffer.id(), 0, static_cast<GLsizeiptr>(bytes.size()), bytes.data());
  return bytes;
}

TEST(PixelPack, BothShapesWriteTheTargetsRowsWithOrWithoutAlpha) {
  auto context = lgh::GlContext::create(lgh::test::rendererOptions());
  std::mt19937 random(7);
  for (const auto [width, height] : {std::pair{1, 1}, {5, 3}, {13, 7}, {37, 19}, {256, 256}}) {
    lgh::FrameTargets targets;
    targets.resize(width, height);
    std::vector<std::uint8_t> codes(static_cast<std::size_t>(width) * height * 4);
    for (std::uint8_t& code : codes) code = static_cast<std::uint8_t>(random());
    glTextureSubImage2D(targets.output(lgh::OutputPixels::Display8).texture.id(), 0, 0, 0, width,
                        height, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, codes.data());
    for (const auto layout : {lgh::FramePixels::Layout::Rgb8, lgh::FramePixels::Layout::Rgba8}) {
      const std::size_t channels = layout == lgh::FramePixels::Layout::Rgb8 ? 3 : 4;
      std::vector<std::uint8_t> expected;
      for (std::size_t i = 0; i < codes.size(); ++i) {
        if (i % 4 < channels) expected.push_back(codes[i]);
      }
      const std::string size = fmt::format("{}x{} {} channels", width, height, channels);
      EXPECT_EQ(packed(lgh::PackShape::Shader, targets, layout), expected) << size;
      EXPECT_EQ(packed(lgh::PackShape::DriverCopy, targets, layout), expected) << size;
    }
  }
}

}  // namespace
