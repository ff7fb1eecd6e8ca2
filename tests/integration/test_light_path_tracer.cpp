// The light paths on the Vulkan tracer (vk/shadow_tracer.hpp, "Light paths"), on lavapipe, below
// the frame (tests/integration/test_gi.cpp tests them through it): the whole generation is one
// submission into the VPL buffer, read back here through its staging mapping.
//  - every slot of the paths is written and the slots left over are cleared, whatever the buffer
//    held; the VPLs are finite, and a grey ground under a point light gets lit VPLs;
//  - the same batch gives the same bytes again and on the other tracing path;
//  - the submission's timestamps: the traces and the kernels inside the whole, once;
//  - batches the buffer cannot hold, too many bounces, more slots than VPLs and semaphores never
//    exported are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "context/gl_context.hpp"
#include "gi/gi_source_buffer.hpp"
#include "gi/gi_sources.hpp"
#include "gi/hit_geometry.hpp"
#include "gl/gl_api.hpp"
#include "lgh/error.hpp"
#include "lightgrid/lgh_types.hpp"
#include "passes/light_buffer.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"
#include "vk/shadow_tracer.hpp"

namespace {

using lgh::vk::LightPathBatch;
using lgh::vk::ShadowTracer;
using lgh::vk::TracePath;
using lgh::vk::Transport;

constexpr std::uint32_t kBounces = 3;

lgh::Mesh quad(float size, float height, bool facingDown) {
  lgh::Primitive primitive;
  for (const glm::vec2 corner :
       {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
    primitive.vertices.push_back({.position = {size * corner.x, height, size * corner.y}});
  }
  primitive.indices = facingDown ? std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}
                                 : std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2};
  primitive.material = 0;
  lgh::Mesh mesh;
  mesh.primitives.push_back(std::move(primitive));
  return mesh;
}

// A grey ground at y = 0 and a grey ceiling at y = 4, 100 m wide, both facing the light between
// them: few paths leave.
lgh::Scene groundAndCeiling() {
  lgh::Scene scene;
  scene.name = "ground and ceiling";
  scene.meshes.push_back(quad(50.0F, 0.0F, false));
  scene.meshes.push_back(quad(50.0F, 4.0F, true));
  scene.instances.push_back({.mesh = 0, .world = glm::mat4(1.0F)});
  scene.instances.push_back({.mesh = 1, .world = glm::mat4(1.0F)});
  scene.computeBounds();
  return scene;
}

std::vector<lgh::Material> greyMaterials() {
  lgh::Material grey;
  grey.name = "grey";
  grey.baseColorFactor = glm::vec4(0.5F, 0.5F, 0.5F, 1.0F);
  grey.metallicFactor = 0.0F;
  grey.doubleSided = true;
  return {grey};
}

lgh::vk::DeviceUuid glDeviceUuid() {
  lgh::vk::DeviceUuid uuid{};
  glGetUnsignedBytei_vEXT(GL_DEVICE_UUID_EXT, 0, uuid.data());
  return uuid;
}

class LightPathTracerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context = lgh::GlContext::create(lgh::test::rendererOptions());
    tracer = ShadowTracer::create(glDeviceUuid());
    scene = std::make_unique<lgh::Scene>(groundAndCeiling());
    traced = tracer->buildScene(*scene);
    geometry = std::make_unique<lgh::HitGeometry>(*scene, greyMaterials());
    lgh::LightDesc light;
    light.position = {0.0F, 2.0F, 0.0F};
    light.intensity = 3.0F;
    lights = {light};
    sources = lgh::buildGiSources(lights, geometry->emissiveTriangles(), scene->bounds);
    for (const lgh::LightDesc& each : lights) packed.push_back(lgh::packLight(each));
  }
  static void TearDownTestSuite() {
    geometry.reset();
    traced.reset();
    scene.reset();
    tracer.reset();
    context.reset();
  }

  static LightPathBatch batch(std::uint32_t paths, std::uint32_t vplCount) {
    const glm::vec4 sphere = lgh::giSceneSphere(*scene);
    const glm::vec3 low = scene->bounds.min;
    const glm::vec3 high = scene->bounds.max;
    return {.paths = paths,
            .vplCount = vplCount,
            .bounces = kBounces,
            .seed = 7,
            .emissionSlot = false,
            .surfaceOffset = lgh::giSurfaceOffset(*scene),
            .sceneSphere = {sphere.x, sphere.y, sphere.z, sphere.w},
            .sceneMin = {low.x, low.y, low.z},
            .sceneMax = {high.x, high.y, high.z},
            .sourceCount = static_cast<std::uint32_t>(sources.sources.size()),
            .sources = std::as_bytes(std::span(sources.sources)),
            .lights = std::as_bytes(std::span(packed))};
  }

  // Traces `request` through the staging buffer, which is filled with 0xFF first, and returns the
  // VPLs.
  static std::vector<lgh::PointLight> trace(TracePath path, const LightPathBatch& request) {
    const auto& buffers = tracer->vplBuffers(request.vplCount, Transport::Staging);
    std::memset(buffers.vpls.mapped, 0xFF, request.vplCount * sizeof(lgh::PointLight));
    tracer->traceLightPaths(*traced, path, geometry->lightPathScene(), request, false);
    std::vector<lgh::PointLight> vpls(request.vplCount);
    std::memcpy(vpls.data(), buffers.vpls.mapped, vpls.size() * sizeof(lgh::PointLight));
    return vpls;
  }

  static TracePath anyPath() {
    return tracer->supports(TracePath::RayQuery) ? TracePath::RayQuery : TracePath::Pipeline;
  }

  static inline std::unique_ptr<lgh::GlContext> context;
  static inline std::unique_ptr<ShadowTracer> tracer;
  static inline std::unique_ptr<lgh::Scene> scene;
  static inline std::unique_ptr<lgh::vk::TraceScene> traced;
  static inline std::unique_ptr<lgh::HitGeometry> geometry;
  static inline std::vector<lgh::LightDesc> lights;
  static inline lgh::GiSourceTable sources;
  static inline std::vector<lgh::GpuLight> packed;
};

bool dark(const lgh::PointLight& vpl) {
  return vpl.intensityPad.r == 0.0F && vpl.intensityPad.g == 0.0F && vpl.intensityPad.b == 0.0F;
}

TEST_F(LightPathTracerTest, EverySlotIsWrittenAndTheRestCleared) {
  constexpr std::uint32_t kPaths = 1000;
  constexpr std::uint32_t kLeftOver = 7;
  const std::vector<lgh::PointLight> vpls =
      trace(anyPath(), batch(kPaths, kPaths * kBounces + kLeftOver));
  for (std::uint32_t slot = kPaths * kBounces; slot < vpls.size(); ++slot) {
    EXPECT_TRUE(dark(vpls[slot]) && vpls[slot].positionPad == glm::vec4(0.0F)) << "slot " << slot;
  }
  std::array<std::uint32_t, kBounces> lit{};
  for (std::uint32_t bounce = 0; bounce < kBounces; ++bounce) {
    for (std::uint32_t path = 0; path < kPaths; ++path) {
      const lgh::PointLight& vpl = vpls[bounce * kPaths + path];
      ASSERT_TRUE(std::isfinite(vpl.positionPad.x) && std::isfinite(vpl.positionPad.y) &&
                  std::isfinite(vpl.intensityPad.r))
          << "bounce " << bounce + 1 << ", path " << path;
      ASSERT_GE(vpl.intensityPad.r, 0.0F);
      if (dark(vpl)) continue;
      ++lit[bounce];
      // On the ground or the ceiling.
      EXPECT_TRUE(std::abs(vpl.positionPad.y) < 1e-3F || std::abs(vpl.positionPad.y - 4.0F) < 1e-3F)
          << vpl.positionPad.y;
    }
  }
  std::cout << fmt::format("light paths: lit VPLs per bounce {} / {} / {} of {}\n", lit[0], lit[1],
                           lit[2], kPaths);
  // Between two planes 100 m wide and 4 m apart, most paths hit one at every bounce.
  for (const std::uint32_t count : lit) EXPECT_GT(count, kPaths / 2);
}

TEST_F(LightPathTracerTest, TheSameBatchGivesTheSameBytesOnEitherPath) {
  const LightPathBatch request = batch(600, 600 * kBounces);
  const auto first = trace(anyPath(), request);
  const auto again = trace(anyPath(), request);
  EXPECT_EQ(std::memcmp(first.data(), again.data(), first.size() * sizeof(lgh::PointLight)), 0);
  if (!tracer->supports(TracePath::RayQuery) || !tracer->supports(TracePath::Pipeline)) {
    GTEST_SKIP() << "one tracing path only";
  }
  const auto pipeline = trace(TracePath::Pipeline, request);
  EXPECT_EQ(std::memcmp(first.data(), pipeline.data(), first.size() * sizeof(lgh::PointLight)), 0);
}

TEST_F(LightPathTracerTest, TimestampsSpanTheStepsOfTheSubmission) {
  tracer->collectLightPathTimings();
  trace(anyPath(), batch(2000, 2000 * kBounces));
  const lgh::vk::LightPathTimings timings = tracer->collectLightPathTimings();
  EXPECT_TRUE(timings.traced);
  EXPECT_GT(timings.totalMs, 0.0);
  double steps = timings.emitMs + timings.raysMs;
  for (const double bounce : timings.bounceMs) steps += bounce;
  EXPECT_GT(timings.raysMs, 0.0);
  // The steps' timestamps follow each other: their rows add up to the whole.
  EXPECT_NEAR(steps, timings.totalMs, 1e-3);
  EXPECT_FALSE(tracer->collectLightPathTimings().traced) << "nothing traced since";
}

TEST_F(LightPathTracerTest, BadBatchesAreRefused) {
  const auto expectInvalid = [](const LightPathBatch& request, bool useSemaphores,
                                const char* what) {
    try {
      tracer->traceLightPaths(*traced, anyPath(), geometry->lightPathScene(), request,
                              useSemaphores);
      ADD_FAILURE() << what << ": no error";
    } catch (const lgh::Error& error) {
      EXPECT_EQ(error.code(), lgh::ErrorCode::Invalid) << what << ": " << error.what();
    }
  };
  tracer->vplBuffers(300, Transport::Staging);
  expectInvalid(batch(100, 1000000), false, "more VPLs than the buffer holds");
  expectInvalid(batch(101, 300), false, "more slots than VPLs");
  LightPathBatch tooDeep = batch(50, 300);
  tooDeep.bounces = lgh::vk::kMaxLightPathBounces + 1;
  expectInvalid(tooDeep, false, "too many bounces");
  if (!tracer->info().externalSemaphoreFd) {
    expectInvalid(batch(100, 300), true, "semaphores never exported");
  }
  // The tracer still works.
  EXPECT_EQ(trace(anyPath(), batch(100, 300)).size(), 300U);
}

}  // namespace
