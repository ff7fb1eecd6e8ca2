// The shadow ray setup pass (glsl/shadow_ray_setup.comp) on a G-buffer written by hand, on
// llvmpipe: a pixel gets a ray for a direct light only where the direct lighting pass will read
// its bit, that is where the light can light the surface at all (include/light_terms.glsl):
//  - a surface facing the light gets a ray, one facing away gets none, unless it transmits light
//    (KHR_materials_transmission: lit from behind);
//  - an unlit surface, a pixel outside a point light's range and the background get none;
//  - a classic model facing away gets none, whatever its flags byte says (not layer bits there).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "context/gl_context.hpp"
#include "gl/gl_objects.hpp"
#include "gl/software_rasterizer.hpp"
#include "passes/frame_targets.hpp"
#include "passes/light_buffer.hpp"
#include "passes/shadow_ray_setup_pass.hpp"
#include "test_support.hpp"

namespace {

// One pixel of the hand-written G-buffer.
struct Surface {
  bool drawn = true;
  glm::vec3 position{0.0F};
  glm::vec3 normal{0.0F, 0.0F, 1.0F};
  unsigned model = 0;  // MATERIAL_MODEL_* (glsl/include/material_models.glsl)
  unsigned flags = 0;  // layer bits (metallic-roughness) or MATERIAL_CLASSIC_* flags
};

constexpr unsigned kMetallicRoughness = 0;
constexpr unsigned kUnlit = 1;
constexpr unsigned kPhong = 2;
constexpr unsigned kTransmission = 8;  // MATERIAL_LAYER_TRANSMISSION

// How a test runs the pass, and what it wants back.
struct Options {
  std::vector<float>* originW = nullptr;
  bool clearsOrigins = lgh::gl::softwareRasterizer();
  bool unrollsLightLoops = lgh::gl::softwareRasterizer();
  int lightSamples = 1;
  std::vector<glm::vec4>* targets = nullptr;  // every target as written, when given
};

class ShadowRaySetup : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context = lgh::GlContext::create(lgh::test::rendererOptions()); }
  static void TearDownTestSuite() { context.reset(); }

  // The rays the pass sets up for `surfaces` (one row of pixels) and `lights`, every light
  // shadowed with one ray, as the tracer reads them (glsl/vk/include/shadow_rays.glsl): per
  // pixel, per light, whether it got a ray, that is its origin has a surface (w > 0) and its
  // target w >= 0; a pixel without a surface has no rays whatever its targets hold (the pass
  // leaves them alone). The origins' w go to `originW` when given (0: no surface). Both buffers
  // start out holding 9s, so that a pixel whose origin the pass leaves alone shows.
  static std::vector<std::vector<bool>> rays(const std::vector<Surface>& surfaces,
                                             const std::vector<lgh::LightDesc>& lights,
                                             const Options& options = {}) {
    lgh::FrameTargets frame;
    const int width = static_cast<int>(surfaces.size());
    frame.resize(width, 1);
    std::vector<glm::vec4> positions;
    std::vector<glm::vec4> normals;
    std::vector<std::array<std::uint8_t, 4>> materials;
    for (const Surface& s : surfaces) {
      positions.emplace_back(s.position, s.drawn ? 1.0F : 0.0F);
      normals.emplace_back(s.normal, 0.0F);
      materials.push_back(
          {0, 128, static_cast<std::uint8_t>(s.model), static_cast<std::uint8_t>(s.flags)});
    }
    glTextureSubImage2D(frame.gbuffer.position.id(), 0, 0, 0, width, 1, GL_RGBA, GL_FLOAT,
                        positions.data());
    glTextureSubImage2D(frame.gbuffer.normal.id(), 0, 0, 0, width, 1, GL_RGBA, GL_FLOAT,
                        normals.data());
    glTextureSubImage2D(frame.gbuffer.material.id(), 0, 0, 0, width, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                        materials.data());

    lgh::gl::SizedBuffer lightBuffer;
    lgh::uploadLights(lights, lightBuffer);
    const auto raysPerPixel = lights.size() * static_cast<std::size_t>(options.lightSamples);
    const auto rayCount = static_cast<GLsizeiptr>(surfaces.size() * raysPerPixel);
    lgh::gl::Buffer origins;
    lgh::gl::Buffer targets;
    const std::vector<glm::vec4> nines(
        static_cast<std::size_t>(std::max<GLsizeiptr>(width, rayCount)), glm::vec4(9.0F));
    glNamedBufferStorage(origins.id(), width * static_cast<GLsizeiptr>(sizeof(glm::vec4)),
                         nines.data(), GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(targets.id(), rayCount * static_cast<GLsizeiptr>(sizeof(glm::vec4)),
                         nines.data(), GL_DYNAMIC_STORAGE_BIT);
    lgh::ShadowRaySetupInputs inputs;
    inputs.layout.shadowedLights = static_cast<int>(lights.size());
    inputs.layout.lightSamples = options.lightSamples;
    inputs.lights = lightBuffer.id();
    inputs.surfaceOffset = 1e-3F;
    inputs.seed = 12345;
    lgh::ShadowRaySetupPass pass(options.clearsOrigins, options.unrollsLightLoops);
    pass.run(inputs, frame, origins.id(), targets.id());
    std::vector<glm::vec4> written(static_cast<std::size_t>(rayCount));
    glGetNamedBufferSubData(targets.id(), 0, rayCount * static_cast<GLsizeiptr>(sizeof(glm::vec4)),
                            written.data());
    std::vector<glm::vec4> writtenOrigins(surfaces.size());
    glGetNamedBufferSubData(origins.id(), 0, width * static_cast<GLsizeiptr>(sizeof(glm::vec4)),
                            writtenOrigins.data());
    if (options.originW != nullptr) {
      options.originW->clear();
      for (const glm::vec4& origin : writtenOrigins) options.originW->push_back(origin.w);
    }
    if (options.targets != nullptr) *options.targets = written;
    std::vector<std::vector<bool>> result(surfaces.size(), std::vector<bool>(lights.size()));
    for (std::size_t p = 0; p < surfaces.size(); ++p) {
      for (std::size_t l = 0; l < lights.size(); ++l) {
        result[p][l] = writtenOrigins[p].w > 0.0F &&
                       written[p * raysPerPixel + l * options.lightSamples].w >= 0.0F;
      }
    }
    return result;
  }

  static inline std::unique_ptr<lgh::GlContext> context;
};

lgh::LightDesc sunFromAbove() {  // lights surfaces whose normal has +z
  lgh::LightDesc light;
  light.type = lgh::LightType::Directional;
  light.direction = {0.0F, 0.0F, -1.0F};
  return light;
}

TEST_F(ShadowRaySetup, RaysGoOnlyWhereTheLightCanLightTheSurface) {
  const glm::vec3 down(0.0F, 0.0F, -1.0F);
  const std::vector<Surface> surfaces = {
      {},                                                         // facing the light
      {.normal = down},                                           // facing away
      {.normal = down, .flags = kTransmission},                   // facing away, transmits
      {.normal = glm::normalize(glm::vec3(1.0F, 0.0F, 1e-6F))},   // grazing, a hair towards it
      {.model = kUnlit},                                          // unlit
      {.normal = down, .model = kPhong, .flags = kTransmission},  // classic, flags not layers
      {.drawn = false},                                           // background
  };
  const std::vector<std::vector<bool>> got = rays(surfaces, {sunFromAbove()});
  const std::vector<bool> expected = {true, false, true, true, false, false, false};
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t p = 0; p < expected.size(); ++p) EXPECT_EQ(got[p][0], expected[p]) << p;
}

TEST_F(ShadowRaySetup, APointLightGivesNoRaysBeyondItsRange) {
  lgh::LightDesc bulb;
  bulb.type = lgh::LightType::Point;
  bulb.position = {0.0F, 0.0F, 1.0F};
  bulb.range = 2.0F;
  const std::vector<Surface> surfaces = {
      {.position = {0.0F, 0.0F, 0.0F}},  // 1 away
      {.position = {5.0F, 0.0F, 0.0F}},  // beyond the range
  };
  const std::vector<std::vector<bool>> got = rays(surfaces, {bulb, sunFromAbove()});
  EXPECT_TRUE(got[0][0]);
  EXPECT_FALSE(got[1][0]);
  EXPECT_TRUE(got[0][1]);  // the sun reaches both
  EXPECT_TRUE(got[1][1]);
}

// A row of 40 pixels: background, then 8 drawn, then background again. The first 16 make SIMD
// groups of background alone (which skip the pass's work: include/skip_background.glsl), the
// last ones share groups with drawn pixels; every background pixel's origin says it has no
// surface (they start out as 9s here), every drawn one gets its ray: with the origins cleared
// first (a CPU rasteriser's way) and stored by the shader (a GPU's).
TEST_F(ShadowRaySetup, BackgroundPixelsGetNoRaysAloneOrBesideSurfaces) {
  std::vector<Surface> surfaces(40, Surface{.drawn = false});
  for (std::size_t p = 16; p < 24; ++p) surfaces[p] = Surface{};
  surfaces[26] = Surface{};
  for (const bool clearsOrigins : {true, false}) {
    std::vector<float> originW;
    const std::vector<std::vector<bool>> got =
        rays(surfaces, {sunFromAbove()}, {.originW = &originW, .clearsOrigins = clearsOrigins});
    for (std::size_t p = 0; p < surfaces.size(); ++p) {
      EXPECT_EQ(got[p][0], surfaces[p].drawn) << p << (clearsOrigins ? " cleared" : " stored");
      EXPECT_EQ(originW[p], surfaces[p].drawn ? 1.0F : 0.0F) << p;
    }
  }
}

// A CPU rasteriser compiles the pass for the frame's numbers of lights and samples, so that its
// loops over them unroll (passes/light_loops.hpp): the same targets to the bit as the loops give,
// for sized lights of each kind (jittered: the random streams must match too), several samples
// each, and for more lights than the unrolled programs take.
TEST_F(ShadowRaySetup, UnrolledLoopsSetUpTheRaysTheLoopsDo) {
  std::vector<Surface> surfaces(24);
  for (std::size_t p = 0; p < surfaces.size(); ++p) {
    surfaces[p].position = glm::vec3(0.1F * static_cast<float>(p), 0.0F, 0.0F);
    surfaces[p].normal = glm::normalize(glm::vec3(0.05F * static_cast<float>(p), 0.2F, 1.0F));
  }
  surfaces[5].drawn = false;
  const auto lightsOf = [](int count) {
    std::vector<lgh::LightDesc> lights;
    for (int i = 0; i < count; ++i) {
      lgh::LightDesc light;
      light.type = static_cast<lgh::LightType>(i % 3);  // directional, point, spot
      light.position = {0.5F * static_cast<float>(i), 1.0F, 3.0F};
      light.direction = {0.1F, -0.2F, -1.0F};
      light.outerConeAngle = 1.2F;
      light.radius = 0.2F;
      light.angularRadius = 0.05F;
      lights.push_back(light);
    }
    return lights;
  };
  for (const auto& [lightCount, samples] : {std::pair{3, 2}, std::pair{2, 1}, std::pair{11, 1}}) {
    std::vector<glm::vec4> unrolled;
    std::vector<glm::vec4> looped;
    const auto lights = lightsOf(lightCount);
    rays(surfaces, lights,
         {.unrollsLightLoops = true, .lightSamples = samples, .targets = &unrolled});
    rays(surfaces, lights,
         {.unrollsLightLoops = false, .lightSamples = samples, .targets = &looped});
    ASSERT_EQ(unrolled.size(), looped.size());
    int jittered = 0;
    for (std::size_t t = 0; t < unrolled.size(); ++t) {
      if (surfaces[t / (lights.size() * static_cast<std::size_t>(samples))].drawn) {
        EXPECT_EQ(unrolled[t], looped[t]) << lightCount << " lights, target " << t;
        jittered += unrolled[t].w >= 0.0F ? 1 : 0;
      }
    }
    EXPECT_GT(jittered, 20) << "rays were set up";
  }
}

}  // namespace
