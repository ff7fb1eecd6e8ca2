// The direct lighting pass (glsl/direct_lighting.comp) on a G-buffer written by hand, on llvmpipe:
// compiled for the frame's numbers of lights, so that its loops over them unroll (a CPU
// rasteriser's way: passes/light_loops.hpp), it gives the radiance its loops give, to the bit.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "context/gl_context.hpp"
#include "gl/gl_objects.hpp"
#include "passes/direct_lighting_pass.hpp"
#include "passes/frame_targets.hpp"
#include "passes/light_buffer.hpp"
#include "test_support.hpp"

namespace {

constexpr int kWidth = 24;
constexpr int kHeight = 8;

class DirectLightingPassTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context = lgh::GlContext::create(lgh::test::rendererOptions()); }
  static void TearDownTestSuite() { context.reset(); }

  // A G-buffer of metallic-roughness surfaces facing +z at various roughness and metalness,
  // every fifth pixel background.
  static void writeGBuffer(lgh::FrameTargets& frame) {
    frame.resize(kWidth, kHeight);
    std::vector<glm::vec4> positions;
    std::vector<glm::vec4> normals;
    std::vector<std::array<std::uint8_t, 4>> albedo;
    std::vector<std::array<std::uint8_t, 4>> material;
    for (int p = 0; p < kWidth * kHeight; ++p) {
      const int column = p % kWidth;
      const int row = p / kWidth;
      const float x = 0.1F * static_cast<float>(column);
      const float y = 0.1F * static_cast<float>(row);
      positions.emplace_back(x, y, 0.0F, p % 5 == 4 ? 0.0F : 1.0F);
      normals.emplace_back(glm::normalize(glm::vec3(0.3F * x - 0.3F, 0.2F * y, 1.0F)), 0.0F);
      albedo.push_back({static_cast<std::uint8_t>(40 + 9 * (p % 20)), 128, 200, 255});
      material.push_back({static_cast<std::uint8_t>(p * 37 % 256),
                          static_cast<std::uint8_t>(20 + p * 11 % 230), 0, 0});
    }
    const auto upload = [](const lgh::gl::Texture& texture, GLenum type, const void* data) {
      glTextureSubImage2D(texture.id(), 0, 0, 0, kWidth, kHeight, GL_RGBA, type, data);
    };
    upload(frame.gbuffer.position, GL_FLOAT, positions.data());
    upload(frame.gbuffer.normal, GL_FLOAT, normals.data());
    upload(frame.gbuffer.albedo, GL_UNSIGNED_BYTE, albedo.data());
    upload(frame.gbuffer.material, GL_UNSIGNED_BYTE, material.data());
  }

  // `count` lights of each kind in turn, with colours, ranges and cones that all matter.
  static std::vector<lgh::LightDesc> lights(int count) {
    std::vector<lgh::LightDesc> result;
    for (int i = 0; i < count; ++i) {
      lgh::LightDesc light;
      light.type = static_cast<lgh::LightType>(i % 3);
      light.position = {0.4F * static_cast<float>(i), 0.3F, 1.5F};
      light.direction = {0.2F - 0.1F * static_cast<float>(i), -0.1F, -1.0F};
      light.color = {1.0F, 0.8F - 0.05F * static_cast<float>(i), 0.6F};
      light.intensity = 1.0F + 0.5F * static_cast<float>(i);
      light.ambient = {0.01F, 0.02F, 0.03F};
      light.range = i % 2 == 0 ? 0.0F : 6.0F;
      light.outerConeAngle = 1.0F;
      light.innerConeAngle = 0.4F;
      result.push_back(light);
    }
    return result;
  }

  // The direct radiance of `lightCount` lights, the first `shadowed` of them with `samples` rays
  // each whose visibility bits are random.
  static std::vector<std::uint16_t> radiance(int lightCount, int shadowed, int samples,
                                             bool unrolls) {
    lgh::FrameTargets frame;
    writeGBuffer(frame);
    lgh::gl::SizedBuffer lightBuffer;
    lgh::uploadLights(lights(lightCount), lightBuffer);
    lgh::DirectLightingInputs inputs;
    inputs.lights = lightBuffer.id();
    inputs.lightCount = lightCount;
    inputs.shadows.shadowedLights = shadowed;
    inputs.shadows.lightSamples = samples;
    inputs.ambient = 0.05F;
    inputs.emission = false;
    std::mt19937 random(99);
    std::vector<std::uint32_t> words(
        static_cast<std::size_t>(kWidth * kHeight * std::max(inputs.shadows.words(), 1)));
    for (std::uint32_t& word : words) word = random();
    lgh::gl::Buffer visibility;
    glNamedBufferStorage(visibility.id(),
                         static_cast<GLsizeiptr>(words.size() * sizeof(std::uint32_t)),
                         words.data(), 0);
    inputs.visibility = visibility.id();
    lgh::CameraMatrices camera;
    camera.position = glm::vec3(1.0F, 0.5F, 4.0F);
    lgh::DirectLightingPass pass(unrolls);
    pass.run(inputs, camera, frame);
    std::vector<std::uint16_t> texels(static_cast<std::size_t>(kWidth * kHeight * 4));
    glGetTextureImage(frame.direct.id(), 0, GL_RGBA, GL_HALF_FLOAT,
                      static_cast<GLsizei>(texels.size() * sizeof(std::uint16_t)), texels.data());
    return texels;
  }

  static inline std::unique_ptr<lgh::GlContext> context;
};

TEST_F(DirectLightingPassTest, UnrolledLoopsLightThePixelsAsTheLoopsDo) {
  for (const auto& [count, shadowed, samples] :
       {std::array{2, 2, 1}, std::array{5, 3, 2}, std::array{1, 0, 1}, std::array{12, 4, 1}}) {
    const std::vector<std::uint16_t> unrolled = radiance(count, shadowed, samples, true);
    const std::vector<std::uint16_t> looped = radiance(count, shadowed, samples, false);
    ASSERT_EQ(unrolled, looped) << count << " lights, " << shadowed << " shadowed x " << samples;
    int lit = 0;
    for (std::size_t t = 0; t < unrolled.size(); t += 4) lit += unrolled[t] != 0 ? 1 : 0;
    EXPECT_GT(lit, kWidth * kHeight / 2) << count << " lights light the surfaces";
  }
}

}  // namespace
