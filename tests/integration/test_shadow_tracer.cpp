// The Vulkan shadow tracer on Mesa's lavapipe, created from the device UUID of a real GL context
// (llvmpipe), with small scenes built in code:
//  - a wrong UUID is Unavailable and names the devices found;
//  - a box above a ground quad shadows the ground under it from a point light and from a light
//    at infinity, and leaves the ground far from it lit; w < 0 targets and pixels with
//    origin.w <= 0 give 0 bits, and every word is written (ray counts 1, 31, 32, 33, 64);
//  - both paths set the same bits on a few thousand random rays (open scene: all visible; box
//    scene: identical words); an empty scene is fully visible;
//  - interop buffers come with fds and sizes; the buffers only grow, each reallocation a new
//    generation; GPU times are collected; scenes are built and traced again and again;
//  - Vulkan failures become lgh::Error(Internal) naming the call and the VkResult (a lost device
//    says so), and no Vulkan driver at all is Unavailable.
// The round trips use staging buffers: llvmpipe cannot back GL buffers with lavapipe's memory.
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <chrono>
#include <cstring>
#include <iostream>
#include <memory>
#include <random>
#include <thread>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "context/gl_context.hpp"
#include "lgh/error.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"
#include "vk/shadow_tracer.hpp"
#include "vk/vulkan_errors.hpp"

namespace {

using lgh::vk::DeviceUuid;
using lgh::vk::RayBatchShape;
using lgh::vk::ShadowTracer;
using lgh::vk::TraceParams;
using lgh::vk::TracePath;
using lgh::vk::TraceScene;
using lgh::vk::Transport;

// The scene: a ground quad over [-10, 10]^2 at y = 0 and a box over [-1, 1] x [1.5, 2.5] x
// [-1, 1] (a unit cube placed by its instance). A point light at (0, 5, 0) shadows the ground
// within |x|, |z| <= 5/3.5 of the axis (the box's bottom face) and lights it beyond 2.
const glm::vec3 kPointLight{0.0F, 5.0F, 0.0F};
constexpr float kLift = 1e-3F;  // origins sit this far above the ground

lgh::Mesh triangles(const std::vector<glm::vec3>& positions, std::vector<std::uint32_t> indices) {
  lgh::Primitive primitive;
  for (const glm::vec3& position : positions) primitive.vertices.push_back({.position = position});
  primitive.indices = std::move(indices);
  lgh::Mesh mesh;
  mesh.primitives.push_back(std::move(primitive));
  return mesh;
}

lgh::Mesh groundQuad() {
  return triangles({{-10, 0, -10}, {10, 0, -10}, {10, 0, 10}, {-10, 0, 10}}, {0, 1, 2, 0, 2, 3});
}

lgh::Mesh unitCube() {
  std::vector<glm::vec3> corners;
  corners.reserve(8);
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back((i & 1) != 0 ? 1 : -1, (i & 2) != 0 ? 1 : -1, (i & 4) != 0 ? 1 : -1);
  }
  return triangles(corners, {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                             2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3});
}

lgh::Scene groundScene() {
  lgh::Scene scene;
  scene.name = "ground";
  scene.meshes.push_back(groundQuad());
  scene.instances.push_back({.mesh = 0, .world = glm::mat4(1.0F)});
  return scene;
}

lgh::Scene boxScene() {
  lgh::Scene scene = groundScene();
  scene.name = "box";
  scene.meshes.push_back(unitCube());
  const glm::mat4 box =
      glm::scale(glm::translate(glm::mat4(1.0F), {0.0F, 2.0F, 0.0F}), {1.0F, 0.5F, 1.0F});
  scene.instances.push_back({.mesh = 1, .world = box});
  return scene;
}

// A batch in CPU memory, laid out as shadow_tracer.hpp says.
struct Batch {
  RayBatchShape shape;
  std::vector<glm::vec4> origins;
  std::vector<glm::vec4> targets;

  Batch(std::uint32_t width, std::uint32_t height, std::uint32_t rays)
      : shape{.width = width, .height = height, .raysPerPixel = rays},
        origins(shape.pixels()),
        targets(shape.pixels() * rays) {}
  glm::vec4& target(std::size_t pixel, std::uint32_t ray) {
    return targets[pixel * shape.raysPerPixel + ray];
  }
};

// A width x height grid of origins on the ground over [-4, 4]^2.
Batch groundGrid(std::uint32_t width, std::uint32_t height, std::uint32_t rays) {
  Batch batch(width, height, rays);
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const float gx = -4.0F + 8.0F * (static_cast<float>(x) + 0.5F) / static_cast<float>(width);
      const float gz = -4.0F + 8.0F * (static_cast<float>(y) + 0.5F) / static_cast<float>(height);
      batch.origins[std::size_t{y} * width + x] = {gx, kLift, gz, 1.0F};
    }
  }
  return batch;
}

bool bit(const std::vector<std::uint32_t>& words, std::uint32_t wordsPerPixel, std::size_t pixel,
         std::uint32_t ray) {
  return ((words[pixel * wordsPerPixel + ray / 32] >> (ray % 32)) & 1U) != 0;
}

// GL_DEVICE_UUID_EXT is indexed (one per device of the context): the indexed query, device 0.
DeviceUuid glDeviceUuid() {
  DeviceUuid uuid{};
  glGetUnsignedBytei_vEXT(GL_DEVICE_UUID_EXT, 0, uuid.data());
  return uuid;
}

class ShadowTracerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context = lgh::GlContext::create(lgh::test::rendererOptions());
    ASSERT_TRUE(lgh::gl::api("GL_EXT_memory_object").EXT_memory_object != 0)
        << "llvmpipe offers GL_EXT_memory_object";
    uuid = glDeviceUuid();
    tracer = ShadowTracer::create(uuid);
    box = tracer->buildScene(boxScene());
    ground = tracer->buildScene(groundScene());
  }
  static void TearDownTestSuite() {
    ground.reset();
    box.reset();
    tracer.reset();
    context.reset();
  }

  // Puts `batch` into lane `lane`'s staging buffers, the visibility filled with ones (so that a
  // word the trace leaves alone shows).
  static void fillLane(const Batch& batch, lgh::vk::RayLane lane) {
    const auto& buffers = tracer->rayBuffers(batch.shape, Transport::Staging, lane);
    std::memcpy(buffers.origins.mapped, batch.origins.data(),
                batch.origins.size() * sizeof(glm::vec4));
    std::memcpy(buffers.targets.mapped, batch.targets.data(),
                batch.targets.size() * sizeof(glm::vec4));
    std::memset(buffers.visibility.mapped, 0xFF,
                batch.shape.pixels() * batch.shape.words() * sizeof(std::uint32_t));
  }
  // Lane `lane`'s visibility words for `batch`'s shape.
  static std::vector<std::uint32_t> laneWords(const Batch& batch, lgh::vk::RayLane lane) {
    const auto& buffers = tracer->rayBuffers(batch.shape, Transport::Staging, lane);
    std::vector<std::uint32_t> words(batch.shape.pixels() * batch.shape.words());
    std::memcpy(words.data(), buffers.visibility.mapped, words.size() * sizeof(std::uint32_t));
    return words;
  }

  // Traces `batch` through staging buffers; the visibility words come back.
  static std::vector<std::uint32_t> trace(TracePath path, const TraceScene& scene,
                                          const Batch& batch, const TraceParams& params = {}) {
    fillLane(batch, 0);
    tracer->trace(scene, path, batch.shape, params, false);
    return laneWords(batch, 0);
  }

  // A path the device offers: ray query where it has it.
  static TracePath anyPath() {
    return tracer->supports(TracePath::RayQuery) ? TracePath::RayQuery : TracePath::Pipeline;
  }

  static inline std::unique_ptr<lgh::GlContext> context;
  static inline DeviceUuid uuid{};
  static inline std::unique_ptr<ShadowTracer> tracer;
  static inline std::unique_ptr<TraceScene> box;
  static inline std::unique_ptr<TraceScene> ground;
};

// Tests that run once per tracing path (skipped where the device lacks it).
class ShadowTracerPath : public ShadowTracerTest, public ::testing::WithParamInterface<TracePath> {
 protected:
  void SetUp() override {
    if (!tracer->supports(GetParam())) {
      GTEST_SKIP() << lgh::enumName(GetParam()) << " is not offered by "
                   << tracer->info().deviceName;
    }
  }
  std::vector<std::uint32_t> trace(const TraceScene& scene, const Batch& batch,
                                   const TraceParams& params = {}) {
    return ShadowTracerTest::trace(GetParam(), scene, batch, params);
  }
};

TEST_F(ShadowTracerTest, CreatesOnTheGlDeviceWithBothPathsOnLavapipe) {
  const auto& info = tracer->info();
  EXPECT_NE(info.deviceName.find("llvmpipe"), std::string::npos) << info.deviceName;
  EXPECT_FALSE(info.driverName.empty());
  EXPECT_EQ(info.apiVersion.substr(0, 2), "1.");
  EXPECT_TRUE(info.rayQuery);
  EXPECT_TRUE(info.rayTracingPipeline);
  EXPECT_TRUE(info.externalMemoryFd);
  EXPECT_GT(info.createMs, 0.0);
  EXPECT_TRUE(tracer->supports(TracePath::RayQuery));
  EXPECT_TRUE(tracer->supports(TracePath::Pipeline));
}

TEST_F(ShadowTracerTest, AWrongUuidIsUnavailableAndNamesTheDevicesFound) {
  DeviceUuid wrong{};
  wrong.fill(0xAB);
  try {
    ShadowTracer::create(wrong);
    FAIL() << "created a tracer on a device that does not exist";
  } catch (const lgh::Error& error) {
    EXPECT_EQ(error.code(), lgh::ErrorCode::Unavailable);
    const std::string& message = error.message();
    EXPECT_NE(message.find("abababab-abab-abab-abab-abababababab"), std::string::npos) << message;
    EXPECT_NE(message.find("llvmpipe"), std::string::npos) << message;
    const std::string glDevice =
        fmt::format("{:02x}{:02x}{:02x}{:02x}-", uuid[0], uuid[1], uuid[2], uuid[3]);
    EXPECT_NE(message.find(glDevice), std::string::npos) << message;
  }
}

TEST_F(ShadowTracerTest, ScenesReportTheirTrianglesMemoryAndBuildTime) {
  EXPECT_EQ(box->triangleCount(), 2U + 12U);
  EXPECT_EQ(ground->triangleCount(), 2U);
  EXPECT_GT(box->gpuBytes(), ground->gpuBytes());
  EXPECT_GT(box->buildGpuMs(), 0.0);
  std::cout << fmt::format("box scene: {} bytes, built in {:.3f} ms (GPU)\n", box->gpuBytes(),
                           box->buildGpuMs());
}

TEST_P(ShadowTracerPath, TheBoxShadowsTheGroundUnderItFromAPointLight) {
  Batch batch = groundGrid(32, 32, 1);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) batch.target(p, 0) = {kPointLight, 1.0F};
  const auto words = trace(*box, batch);
  int shadowed = 0;
  int lit = 0;
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
    const glm::vec4 o = batch.origins[p];
    const float reach = std::max(std::abs(o.x), std::abs(o.z));
    if (reach < 1.3F) {
      EXPECT_FALSE(bit(words, 1, p, 0)) << "under the box at " << o.x << ", " << o.z;
      ++shadowed;
    } else if (reach > 2.1F) {
      EXPECT_TRUE(bit(words, 1, p, 0)) << "far from the box at " << o.x << ", " << o.z;
      ++lit;
    }
    EXPECT_EQ(words[p] & ~1U, 0U) << "bits past the batch's rays";
  }
  EXPECT_GT(shadowed, 40);
  EXPECT_GT(lit, 400);
  // The open scene: every ray reaches the light.
  const auto open = trace(*ground, batch);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) EXPECT_EQ(open[p], 1U) << p;
}

TEST_P(ShadowTracerPath, TheBoxShadowsTheGroundFromLightsAtInfinity) {
  Batch batch = groundGrid(32, 32, 2);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
    batch.target(p, 0) = {0.0F, 3.0F, 0.0F, 0.0F};  // straight up (not unit length)
    batch.target(p, 1) = {1.0F, 1.0F, 0.0F, 0.0F};  // 45 degrees towards +x
  }
  const auto words = trace(*box, batch);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
    const glm::vec4 o = batch.origins[p];
    const bool underBox = std::abs(o.x) < 0.95F && std::abs(o.z) < 0.95F;
    const bool clearOfBox = std::abs(o.x) > 1.05F || std::abs(o.z) > 1.05F;
    if (underBox) EXPECT_FALSE(bit(words, 1, p, 0)) << o.x << ", " << o.z;
    if (clearOfBox) EXPECT_TRUE(bit(words, 1, p, 0)) << o.x << ", " << o.z;
    // Towards +x the shadow moves to x - y: [-1 - 2.5, 1 - 1.5] = [-3.5, -0.5].
    const bool inSlantedShadow = o.x > -3.4F && o.x < -0.6F && std::abs(o.z) < 0.95F;
    const bool clearOfSlanted = o.x > -0.4F || o.x < -3.6F || std::abs(o.z) > 1.05F;
    if (inSlantedShadow) EXPECT_FALSE(bit(words, 1, p, 1)) << o.x << ", " << o.z;
    if (clearOfSlanted) EXPECT_TRUE(bit(words, 1, p, 1)) << o.x << ", " << o.z;
  }
  // A light at infinity beyond tMaxInfinite is not occluded by what lies past it.
  TraceParams shortRays;
  shortRays.tMaxInfinite = 1.0F;
  const auto short_ = trace(*box, batch, shortRays);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) EXPECT_EQ(short_[p], 3U) << p;
}

TEST_P(ShadowTracerPath, NoRayForNegativeWTargetsOrInactivePixels) {
  Batch batch = groundGrid(8, 4, 3);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
    batch.origins[p].x += 6.0F;  // clear of the box: every ray that is traced reaches its end
    batch.target(p, 0) = {kPointLight, 1.0F};
    batch.target(p, 1) = {kPointLight, -1.0F};
    batch.target(p, 2) = {0.0F, 1.0F, 0.0F, 0.0F};
  }
  batch.origins[5].w = 0.0F;
  batch.origins[6].w = -1.0F;
  const auto words = trace(*box, batch);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
    EXPECT_EQ(words[p], (p == 5 || p == 6) ? 0U : 0b101U) << p;
  }
}

TEST_P(ShadowTracerPath, EveryWordIsWrittenAtEveryRayCount) {
  // Under the box, rays cycle through: to the light above (occluded), to a light off to the side
  // (visible), no ray.
  for (std::uint32_t rays : {1U, 31U, 32U, 33U, 64U}) {
    Batch batch(4, 3, rays);
    for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
      batch.origins[p] = {0.1F * static_cast<float>(p) - 0.5F, kLift, 0.2F, 1.0F};
      for (std::uint32_t r = 0; r < rays; ++r) {
        const glm::vec4 targets[3] = {{kPointLight, 1.0F}, {8.0F, 5.0F, 0.0F, 1.0F}, {0, 1, 0, -1}};
        batch.target(p, r) = targets[r % 3];
      }
    }
    const auto words = trace(*box, batch);
    const std::uint32_t perPixel = batch.shape.words();
    ASSERT_EQ(words.size(), batch.shape.pixels() * perPixel);
    for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
      for (std::uint32_t r = 0; r < perPixel * 32; ++r) {
        EXPECT_EQ(bit(words, perPixel, p, r), r < rays && r % 3 == 1)
            << rays << " rays, pixel " << p << ", ray " << r;
      }
    }
  }
}

TEST_P(ShadowTracerPath, AnEmptySceneIsFullyVisible) {
  lgh::Scene instancesOnly;  // no meshes, an instance of nothing
  instancesOnly.instances.push_back({.mesh = 3});
  lgh::Scene meshesOnly = boxScene();  // triangles, but no instance places them
  meshesOnly.instances.clear();
  Batch batch = groundGrid(4, 4, 2);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
    batch.target(p, 0) = {kPointLight, 1.0F};
    batch.target(p, 1) = {0.0F, 1.0F, 0.0F, 0.0F};
  }
  for (const lgh::Scene& scene : {lgh::Scene{}, instancesOnly, meshesOnly}) {
    const auto empty = tracer->buildScene(scene);
    const auto words = trace(*empty, batch);
    for (std::size_t p = 0; p < batch.shape.pixels(); ++p) EXPECT_EQ(words[p], 3U) << p;
  }
}

// The staging transport's asynchronous traces (vk::ShadowTracer::submitTrace, awaitTrace): two
// lanes submitted back to back, one wait for the later, and each lane holds the bits that a
// waited trace() of its batch gives.
TEST_P(ShadowTracerPath, SubmittedTracesInTwoLanesGiveWhatWaitedTracesGive) {
  Batch batch = groundGrid(32, 32, 1);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) batch.target(p, 0) = {kPointLight, 1.0F};
  const std::vector<std::uint32_t> boxWords = trace(*box, batch);
  const std::vector<std::uint32_t> groundWords = trace(*ground, batch);
  ASSERT_NE(boxWords, groundWords);  // the box's shadow shows
  fillLane(batch, 0);
  fillLane(batch, 1);
  const std::uint64_t first = tracer->submitTrace(*box, GetParam(), batch.shape, {}, 0);
  const std::uint64_t second = tracer->submitTrace(*ground, GetParam(), batch.shape, {}, 1);
  EXPECT_EQ(second, first + 1);
  EXPECT_EQ(tracer->lastTrace(), second);
  tracer->awaitTrace(second);  // and so the first
  EXPECT_EQ(laneWords(batch, 0), boxWords);
  EXPECT_EQ(laneWords(batch, 1), groundWords);
  // Their GPU times are banked for the frames that ask, as a waited trace's are.
  EXPECT_GT(tracer->collectTimingsThrough(second).traceGpuMs, 0.0);
}

// traceFinished() asks without waiting (a renderer's poll issues a split frame's last passes only
// once it says so): it turns true for a submitted trace without any wait, the earlier trace is
// finished when the later is, the bits are there by then, and each trace's GPU time is read on
// its own (from the host copy the queue wrote: lavapipe's query read waits for the whole queue).
TEST_P(ShadowTracerPath, TraceFinishedTurnsTrueWithoutAWait) {
  Batch batch = groundGrid(32, 32, 1);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) batch.target(p, 0) = {kPointLight, 1.0F};
  const std::vector<std::uint32_t> boxWords = trace(*box, batch);
  EXPECT_TRUE(tracer->traceFinished(tracer->lastTrace()));
  fillLane(batch, 0);
  fillLane(batch, 1);
  const std::uint64_t first = tracer->submitTrace(*box, GetParam(), batch.shape, {}, 0);
  const std::uint64_t second = tracer->submitTrace(*box, GetParam(), batch.shape, {}, 1);
  const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!tracer->traceFinished(second) && std::chrono::steady_clock::now() < giveUp) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(tracer->traceFinished(second)) << "the trace never finished";
  EXPECT_TRUE(tracer->traceFinished(first));
  EXPECT_EQ(laneWords(batch, 0), boxWords);
  EXPECT_EQ(laneWords(batch, 1), boxWords);
  EXPECT_GT(tracer->collectTimingsThrough(first).traceGpuMs, 0.0);
  EXPECT_GT(tracer->collectTimingsThrough(second).traceGpuMs, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Paths, ShadowTracerPath,
                         ::testing::Values(TracePath::RayQuery, TracePath::Pipeline),
                         [](const auto& info) {
                           return info.param == TracePath::RayQuery ? "RayQuery" : "Pipeline";
                         });

// Random origins on the ground, each with rays to random points above it and in random
// directions into the upper half-space.
Batch randomBatch(std::uint32_t width, std::uint32_t height, std::uint32_t rays) {
  std::mt19937 random(20240611U);
  std::uniform_real_distribution<float> spread(-4.0F, 4.0F);
  std::uniform_real_distribution<float> up(0.1F, 6.0F);
  Batch batch(width, height, rays);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
    batch.origins[p] = {spread(random), kLift, spread(random), 1.0F};
    for (std::uint32_t r = 0; r < rays; ++r) {
      batch.target(p, r) = {spread(random), up(random), spread(random), (r % 2 == 0) ? 1.0F : 0.0F};
    }
  }
  return batch;
}

TEST_F(ShadowTracerTest, BothPathsSetTheSameBits) {
  if (!tracer->supports(TracePath::RayQuery) || !tracer->supports(TracePath::Pipeline)) {
    GTEST_SKIP() << "one tracing path only";
  }
  const Batch batch = randomBatch(64, 32, 4);  // 8192 rays
  trace(TracePath::RayQuery, *ground, batch);  // lavapipe compiles on first use: not timed
  trace(TracePath::Pipeline, *ground, batch);
  tracer->collectTimings();
  const auto openQuery = trace(TracePath::RayQuery, *ground, batch);
  const double queryMs = tracer->collectTimings().traceGpuMs;
  const auto openPipeline = trace(TracePath::Pipeline, *ground, batch);
  const double pipelineMs = tracer->collectTimings().traceGpuMs;
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
    ASSERT_EQ(openQuery[p], 0xFU) << p;
    ASSERT_EQ(openPipeline[p], 0xFU) << p;
  }
  const auto boxQuery = trace(TracePath::RayQuery, *box, batch);
  const auto boxPipeline = trace(TracePath::Pipeline, *box, batch);
  int shadowedRays = 0;
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
    ASSERT_EQ(boxQuery[p], boxPipeline[p]) << "pixel " << p;
    shadowedRays += 4 - std::popcount(boxQuery[p]);
  }
  EXPECT_GT(shadowedRays, 100) << "the box is in the way of some";
  EXPECT_GT(queryMs, 0.0);
  EXPECT_GT(pipelineMs, 0.0);
  std::cout << fmt::format("{} rays, open scene: ray query {:.3f} ms, pipeline {:.3f} ms (GPU)\n",
                           batch.targets.size(), queryMs, pipelineMs);
}

// The ray-query shader interleaves the rows of work groups (include/balanced_tiles.glsl) where the
// pipeline's launch takes pixels as they come: at odd and even counts of rows of 8 x 8 tiles, and
// a last row or column only partly in the batch, both paths set the same bits for every pixel.
TEST_F(ShadowTracerTest, BothPathsSetTheSameBitsWhateverTheRowsOfTiles) {
  if (!tracer->supports(TracePath::RayQuery) || !tracer->supports(TracePath::Pipeline)) {
    GTEST_SKIP() << "one tracing path only";
  }
  for (const auto [width, height] : {std::pair{37U, 19U}, std::pair{30U, 33U}, std::pair{9U, 8U},
                                     std::pair{16U, 41U}, std::pair{5U, 3U}}) {
    const Batch batch = randomBatch(width, height, 2);
    const auto query = trace(TracePath::RayQuery, *box, batch);
    const auto pipeline = trace(TracePath::Pipeline, *box, batch);
    ASSERT_EQ(query.size(), pipeline.size());
    for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
      ASSERT_EQ(query[p], pipeline[p]) << width << "x" << height << " pixel " << p;
    }
  }
}

// A batch that names the tiles its rays lie in (RayBatchShape::tiles, the frame's surface tiles):
// the ray-query path launches those tiles alone and every other pixel's words are zero, so each
// path and the untiled batch set the same bits, at offsets in both axes and for no tile at all.
TEST_F(ShadowTracerTest, ABatchThatNamesItsTilesGetsTheBitsOfTheWholeBatch) {
  for (const auto& [first, count] : {std::pair{std::array{1U, 2U}, std::array{3U, 1U}},
                                     std::pair{std::array{0U, 0U}, std::array{5U, 4U}},
                                     std::pair{std::array{4U, 3U}, std::array{1U, 1U}},
                                     std::pair{std::array{2U, 1U}, std::array{0U, 0U}}}) {
    Batch batch = randomBatch(37, 29, 2);  // 5 x 4 tiles, the last column and row in part
    for (std::uint32_t y = 0; y < 29; ++y) {
      for (std::uint32_t x = 0; x < 37; ++x) {
        const bool inTiles = x / 8 >= first[0] && x / 8 < first[0] + count[0] &&
                             y / 8 >= first[1] && y / 8 < first[1] + count[1];
        if (!inTiles) batch.origins[std::size_t{y} * 37 + x].w = 0.0F;
      }
    }
    const auto whole = trace(anyPath(), *box, batch);
    Batch tiled = batch;
    tiled.shape.tiles = lgh::vk::RayTiles{.first = first, .count = count};
    for (const TracePath path : {TracePath::RayQuery, TracePath::Pipeline}) {
      if (!tracer->supports(path)) continue;
      const auto words = trace(path, *box, tiled);
      ASSERT_EQ(words, whole) << lgh::enumName(path) << " tiles from " << first[0] << ", "
                              << first[1] << ": " << count[0] << " x " << count[1];
    }
    int lit = 0;
    for (const std::uint32_t word : whole) lit += std::popcount(word);
    if (count[0] * count[1] > 0) EXPECT_GT(lit, 0) << "rays in the tiles reach their lights";
    if (count[0] * count[1] == 0) EXPECT_EQ(lit, 0) << "no pixel has rays";
  }
}

TEST_F(ShadowTracerTest, StagingBuffersGrowOnlyAndEachReallocationIsANewGeneration) {
  const auto& first =
      tracer->rayBuffers({.width = 64, .height = 64, .raysPerPixel = 8}, Transport::Staging);
  const std::uint64_t generation = first.generation;
  EXPECT_EQ(first.transport, Transport::Staging);
  EXPECT_GE(first.origins.size, 64U * 64U * 16U);
  EXPECT_GE(first.targets.size, 64U * 64U * 8U * 16U);
  EXPECT_GE(first.visibility.size, 64U * 64U * 4U);
  EXPECT_NE(first.origins.mapped, nullptr);
  EXPECT_EQ(first.origins.fd, -1);
  const auto& smaller =
      tracer->rayBuffers({.width = 16, .height = 16, .raysPerPixel = 1}, Transport::Staging);
  EXPECT_EQ(smaller.generation, generation);
  const auto& larger =
      tracer->rayBuffers({.width = 64, .height = 64, .raysPerPixel = 40}, Transport::Staging);
  EXPECT_EQ(larger.generation, generation + 1);
  EXPECT_GE(larger.visibility.size, 64U * 64U * 2U * 4U);
}

TEST_F(ShadowTracerTest, InteropBuffersComeAsFds) {
  ASSERT_TRUE(tracer->info().externalMemoryFd);
  const RayBatchShape shape{.width = 32, .height = 16, .raysPerPixel = 33};
  const auto staging = tracer->rayBuffers(shape, Transport::Staging).generation;
  const auto& buffers = tracer->rayBuffers(shape, Transport::Interop);
  EXPECT_EQ(buffers.transport, Transport::Interop);
  EXPECT_GT(buffers.generation, staging);
  for (const auto* buffer : {&buffers.origins, &buffers.targets, &buffers.visibility}) {
    EXPECT_GE(buffer->fd, 0);
    EXPECT_GE(buffer->allocationSize, buffer->size);
    EXPECT_TRUE(buffer->dedicated);
    EXPECT_EQ(buffer->mapped, nullptr);
    if (buffer->fd >= 0) close(buffer->fd);  // GL would own them after an import
  }
  EXPECT_GE(buffers.targets.size, 32U * 16U * 33U * 16U);
  EXPECT_GE(buffers.visibility.size, 32U * 16U * 2U * 4U);
  // Tracing into them works too (GL would have written the rays); back to staging afterwards.
  tracer->trace(*box, anyPath(), shape, {}, false);
  const std::uint64_t interop = buffers.generation;
  EXPECT_GT(tracer->rayBuffers(shape, Transport::Staging).generation, interop);
}

TEST_F(ShadowTracerTest, SemaphoresNeedExportableSemaphores) {
  if (tracer->info().externalSemaphoreFd) {
    const auto fds = tracer->exportSemaphores();
    EXPECT_GE(fds.glDone, 0);
    EXPECT_GE(fds.vkDone, 0);
    close(fds.glDone);
    close(fds.vkDone);
    return;
  }
  try {
    tracer->exportSemaphores();
    FAIL() << "exported semaphores the device cannot export";
  } catch (const lgh::Error& error) {
    EXPECT_EQ(error.code(), lgh::ErrorCode::Unavailable) << error.what();
  }
  // Without them, a trace cannot wait on GL.
  const RayBatchShape shape{.width = 4, .height = 4, .raysPerPixel = 1};
  tracer->rayBuffers(shape, Transport::Staging);
  EXPECT_THROW(tracer->trace(*box, anyPath(), shape, {}, true), lgh::Error);
}

TEST_F(ShadowTracerTest, BadBatchesAreRefused) {
  const auto expectCode = [](lgh::ErrorCode code, const auto& call) {
    try {
      call();
      ADD_FAILURE() << "no error";
    } catch (const lgh::Error& error) {
      EXPECT_EQ(error.code(), code) << error.what();
    }
  };
  expectCode(lgh::ErrorCode::Invalid, [] {
    tracer->rayBuffers({.width = 4, .height = 4, .raysPerPixel = 65}, Transport::Staging);
  });
  expectCode(lgh::ErrorCode::Invalid, [] {
    tracer->rayBuffers({.width = 0, .height = 4, .raysPerPixel = 1}, Transport::Staging);
  });
  tracer->rayBuffers({.width = 4, .height = 4, .raysPerPixel = 1}, Transport::Staging);
  expectCode(lgh::ErrorCode::Invalid, [] {
    tracer->trace(*box, anyPath(), {.width = 1024, .height = 1024, .raysPerPixel = 1}, {}, false);
  });
  expectCode(lgh::ErrorCode::Invalid, [] {  // tiles 3 and 4 of a batch 3 tiles wide
    tracer->rayBuffers({.width = 20,
                        .height = 4,
                        .raysPerPixel = 1,
                        .tiles = lgh::vk::RayTiles{.first = {1, 0}, .count = {3, 1}}},
                       Transport::Staging);
  });
}

TEST_F(ShadowTracerTest, ScenesBuildAgainAndTraceManyTimes) {
  Batch batch = groundGrid(16, 16, 2);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
    batch.target(p, 0) = {kPointLight, 1.0F};
    batch.target(p, 1) = {0.0F, 1.0F, 0.0F, 0.0F};
  }
  const auto reference = trace(anyPath(), *box, batch);
  for (int build = 0; build < 2; ++build) {
    const auto again = tracer->buildScene(boxScene());
    for (int i = 0; i < 20; ++i) {
      const TracePath path = i % 2 == 0 ? TracePath::RayQuery : TracePath::Pipeline;
      if (!tracer->supports(path)) continue;
      ASSERT_EQ(trace(path, *again, batch), reference) << "build " << build << ", trace " << i;
    }
  }
  EXPECT_GT(tracer->collectTimings().traceGpuMs, 0.0);
  EXPECT_EQ(tracer->collectTimings().traceGpuMs, 0.0) << "nothing traced since";
}

// A grid of `cells` x `cells` quads (two triangles each) over [0, 1]^2 in the x-z plane.
lgh::Mesh gridMesh(std::uint32_t cells) {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
  const std::uint32_t side = cells + 1;
  for (std::uint32_t z = 0; z < side; ++z) {
    for (std::uint32_t x = 0; x < side; ++x) {
      positions.emplace_back(static_cast<float>(x) / static_cast<float>(cells), 0.0F,
                             static_cast<float>(z) / static_cast<float>(cells));
    }
  }
  for (std::uint32_t z = 0; z < cells; ++z) {
    for (std::uint32_t x = 0; x < cells; ++x) {
      const std::uint32_t corner = z * side + x;
      indices.insert(indices.end(), {corner, corner + side, corner + 1, corner + 1, corner + side,
                                     corner + side + 1});
    }
  }
  return triangles(positions, std::move(indices));
}

// Small scenes build every structure in one buffer and one submission; a scene whose bottom
// levels reach 8 MB builds them apart and compacts them. Both trace alike: the box scene with a
// 250,000-triangle grid far out of the rays' way shadows exactly as the box scene does.
TEST_F(ShadowTracerTest, ALargeCompactedSceneTracesAsTheSmallOne) {
  lgh::Scene large = boxScene();
  large.name = "box and a far grid";
  large.meshes.push_back(gridMesh(354));
  large.instances.push_back(
      {.mesh = 2, .world = glm::translate(glm::mat4(1.0F), {1000.0F, 0.0F, 1000.0F})});
  const auto built = tracer->buildScene(large);
  EXPECT_EQ(built->triangleCount(), box->triangleCount() + std::size_t{2} * 354 * 354);
  EXPECT_GT(built->gpuBytes(), std::size_t{8} << 20) << "the compacted path is taken";
  Batch batch = groundGrid(32, 32, 2);
  for (std::size_t p = 0; p < batch.shape.pixels(); ++p) {
    batch.target(p, 0) = {kPointLight, 1.0F};
    batch.target(p, 1) = {1.0F, 1.0F, 0.0F, 0.0F};
  }
  EXPECT_EQ(trace(anyPath(), *built, batch), trace(anyPath(), *box, batch));
}

TEST(VulkanErrors, FailedCallsBecomeInternalErrorsNamingTheResult) {
  try {
    lgh::vk::translateVulkanErrors(
        "trace", []() -> int { throw ::vk::DeviceLostError("vk::Queue::submit"); });
    FAIL() << "no error";
  } catch (const lgh::Error& error) {
    EXPECT_EQ(error.code(), lgh::ErrorCode::Internal);
    EXPECT_NE(error.message().find("trace: vk::Queue::submit failed: VK_ERROR_DEVICE_LOST"),
              std::string::npos)
        << error.message();
    EXPECT_NE(error.message().find("device is lost"), std::string::npos) << error.message();
  }
  EXPECT_EQ(lgh::vk::resultName(::vk::Result::eErrorOutOfDeviceMemory),
            "VK_ERROR_OUT_OF_DEVICE_MEMORY");
  EXPECT_EQ(lgh::vk::resultName(static_cast<::vk::Result>(-424242)), "VkResult -424242");
  EXPECT_EQ(lgh::vk::translateVulkanErrors("nothing", [] { return 7; }), 7);
}

TEST(ShadowTracerWithoutDriver, IsUnavailable) {
  // An ICD list naming no file: the loader finds no driver (it looks again for each instance).
  ASSERT_EQ(setenv("VK_ICD_FILENAMES", "/nonexistent/icd.json", 1), 0);
  ASSERT_EQ(setenv("VK_DRIVER_FILES", "/nonexistent/icd.json", 1), 0);
  try {
    ShadowTracer::create(DeviceUuid{});
    ADD_FAILURE() << "created a tracer without a driver";
  } catch (const lgh::Error& error) {
    EXPECT_EQ(error.code(), lgh::ErrorCode::Unavailable) << error.what();
    EXPECT_NE(error.message().find("driver"), std::string::npos) << error.message();
  }
  unsetenv("VK_ICD_FILENAMES");
  unsetenv("VK_DRIVER_FILES");
}

}  // namespace
