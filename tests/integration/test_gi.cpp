// Global illumination by light paths (docs/GI.md) on llvmpipe + lavapipe, small:
//  - VPL count, layout and determinism for a fixed seed (the same VPLs twice; another seed,
//    other VPLs); both tracing paths (ray query, pipeline) give the very same VPLs;
//  - energy: in a closed room every path hits, so bounce b's VPLs carry exactly the light's power
//    times albedo^b (/ 2 pi), and the room gathers more light with more bounces, converging;
//  - the light paths read the frame's materials (a request's `materials` colour the bounces);
//  - emissive triangles are area lights: their emission VPLs carry pi L A; directional and spot
//    lights deposit their power;
//  - the light paths' timing rows and decisions; the request's conflicts; no Vulkan: 503.
// The golden image of the demo with one bounce is in test_render_golden.cpp.
#include <gtest/gtest.h>
#include <algorithm>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numeric>

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

#include "context/gl_context.hpp"
#include "frame_pipeline.hpp"
#include "lgh/error.hpp"
#include "lgh/renderer.hpp"
#include "lgh/testing/image_metrics.hpp"
#include "scene/gpu_scene.hpp"
#include "scene/scene_cache.hpp"
#include "shadows/shadow_device.hpp"
#include "test_support.hpp"

namespace {

using json = nlohmann::json;

struct Frame {
  lgh::FrameReport report;
  lgh::LghFrameProbe probe;
};

// A closed cube room of half size 1 centred at (0, 1, 0), faces facing in, one grey material.
lgh::Scene closedRoom(float albedo) {
  lgh::Primitive walls;
  walls.material = 0;
  const glm::vec3 c(0.0F, 1.0F, 0.0F);
  for (int axis = 0; axis < 3; ++axis) {
    for (const float side : {-1.0F, 1.0F}) {
      glm::vec3 n(0.0F);
      n[axis] = -side;  // facing in
      const glm::vec3 u = glm::vec3(axis == 1 ? 1 : 0, axis == 1 ? 0 : 1, 0);
      const glm::vec3 v = glm::cross(n, u);
      const auto base = static_cast<std::uint32_t>(walls.vertices.size());
      const glm::vec3 centre = c - n;
      for (const glm::vec2 corner :
           {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        lgh::Vertex vertex;
        vertex.position = centre + corner.x * u + corner.y * v;
        vertex.normal = n;
        walls.vertices.push_back(vertex);
      }
      for (std::uint32_t i : {0U, 1U, 2U, 0U, 2U, 3U}) walls.indices.push_back(base + i);
    }
  }
  lgh::Scene scene;
  scene.name = fmt::format("closed room {}", albedo);
  scene.meshes.push_back({"walls", {walls}});
  scene.instances.push_back({0, glm::mat4(1.0F)});
  lgh::Material grey;
  grey.baseColorFactor = glm::vec4(glm::vec3(albedo), 1.0F);
  grey.metallicFactor = 0.0F;
  grey.roughnessFactor = 1.0F;
  scene.materials.push_back(grey);
  scene.computeBounds();
  return scene;
}

// The inside of a sphere of radius 1 centred at (0, 1, 0), normals facing in, one grey material.
lgh::Scene sphereRoom(float albedo, int rings, int segments) {
  lgh::Primitive shell;
  shell.material = 0;
  const glm::vec3 c(0.0F, 1.0F, 0.0F);
  for (int ring = 0; ring <= rings; ++ring) {
    const float theta = glm::pi<float>() * static_cast<float>(ring) / static_cast<float>(rings);
    for (int segment = 0; segment <= segments; ++segment) {
      const float phi =
          glm::two_pi<float>() * static_cast<float>(segment) / static_cast<float>(segments);
      const glm::vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      lgh::Vertex vertex;
      vertex.position = c + d;
      vertex.normal = -d;
      shell.vertices.push_back(vertex);
    }
  }
  const auto stride = static_cast<std::uint32_t>(segments + 1);
  for (int ring = 0; ring < rings; ++ring) {
    for (int segment = 0; segment < segments; ++segment) {
      const std::uint32_t a =
          static_cast<std::uint32_t>(ring) * stride + static_cast<std::uint32_t>(segment);
      shell.indices.insert(shell.indices.end(),
                           {a, a + stride, a + stride + 1, a, a + stride + 1, a + 1});
    }
  }
  lgh::Scene scene;
  scene.name = fmt::format("sphere room {}", albedo);
  scene.meshes.push_back({"shell", {shell}});
  scene.instances.push_back({0, glm::mat4(1.0F)});
  lgh::Material grey;
  grey.baseColorFactor = glm::vec4(glm::vec3(albedo), 1.0F);
  grey.metallicFactor = 0.0F;
  grey.roughnessFactor = 1.0F;
  scene.materials.push_back(grey);
  scene.computeBounds();
  return scene;
}

// A white floor of half size 40 at y = 0 and a white cube of half size 0.1 at (0, 10, 0): far
// from the floor, for the energy check.
lgh::Scene boxAboveFloor() {
  lgh::Primitive surfaces;
  surfaces.material = 0;
  const auto quad = [&](const glm::vec3& centre, const glm::vec3& u, const glm::vec3& v) {
    const auto base = static_cast<std::uint32_t>(surfaces.vertices.size());
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    for (const glm::vec2 c :
         {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
      lgh::Vertex vertex;
      vertex.position = centre + c.x * u + c.y * v;
      vertex.normal = n;
      surfaces.vertices.push_back(vertex);
    }
    for (std::uint32_t i : {0U, 1U, 2U, 0U, 2U, 3U}) surfaces.indices.push_back(base + i);
  };
  quad({0, 0, 0}, {0, 0, 40}, {40, 0, 0});  // facing +y
  const glm::vec3 c(0.0F, 10.0F, 0.0F);
  const float h = 0.1F;
  quad(c + glm::vec3(0, h, 0), {0, 0, h}, {h, 0, 0});  // top
  quad(c - glm::vec3(0, h, 0), {h, 0, 0}, {0, 0, h});  // bottom
  quad(c + glm::vec3(h, 0, 0), {0, h, 0}, {0, 0, h});  // +x
  quad(c - glm::vec3(h, 0, 0), {0, 0, h}, {0, h, 0});  // -x
  quad(c + glm::vec3(0, 0, h), {h, 0, 0}, {0, h, 0});  // +z
  quad(c - glm::vec3(0, 0, h), {0, h, 0}, {h, 0, 0});  // -z
  lgh::Scene scene;
  scene.name = "box above floor";
  scene.meshes.push_back({"surfaces", {surfaces}});
  scene.instances.push_back({0, glm::mat4(1.0F)});
  lgh::Material white;
  white.baseColorFactor = glm::vec4(0.8F, 0.8F, 0.8F, 1.0F);
  white.metallicFactor = 0.0F;
  white.roughnessFactor = 1.0F;
  scene.materials.push_back(white);
  scene.computeBounds();
  return scene;
}

class GlobalIllumination : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context = lgh::GlContext::create(lgh::test::rendererOptions());
    device = std::make_unique<lgh::ShadowDevice>();
    cache = std::make_unique<lgh::SceneCache>(lgh::RendererOptions{});
    pipeline = std::make_unique<lgh::FramePipeline>(device.get());
  }
  static void TearDownTestSuite() {
    pipeline.reset();
    cache.reset();
    device.reset();
    context.reset();
  }

  static lgh::RenderRequest request(const json& gi, const std::string& shadowPath = "auto") {
    json body = {{"output", {{"width", 48}, {"height", 36}}},
                 {"settings",
                  {{"shadows", "off"}, {"shadow_path", shadowPath}, {"ambient", 0}, {"gi", gi}}}};
    return lgh::parseRenderRequest(body);
  }

  static Frame render(const lgh::RenderRequest& req, const lgh::CachedScene& scene) {
    Frame frame;
    frame.probe.readVpls = true;
    lgh::gl::GpuTimer timer;
    pipeline->render(req, scene, timer, frame.report, &frame.probe);
    return frame;
  }

  static Frame renderDemo(const json& gi, const std::string& shadowPath = "auto") {
    const lgh::RenderRequest req = request(gi, shadowPath);
    return render(req, *cache->get(req.scene).entry);
  }

  static std::unique_ptr<lgh::CachedScene> cached(lgh::Scene scene) {
    auto entry = std::make_unique<lgh::CachedScene>();
    entry->scene = std::move(scene);
    entry->gpu = std::make_unique<lgh::GpuScene>(entry->scene, lgh::GpuSceneOptions{});
    return entry;
  }

  static bool sameVpls(const Frame& a, const Frame& b) {
    return a.probe.vpls.size() == b.probe.vpls.size() &&
           std::memcmp(a.probe.vpls.data(), b.probe.vpls.data(),
                       a.probe.vpls.size() * sizeof(lgh::PointLight)) == 0;
  }

  static std::size_t litVpls(const Frame& frame) {
    std::size_t lit = 0;
    for (const lgh::PointLight& vpl : frame.probe.vpls) {
      if (glm::length(glm::vec3(vpl.intensityPad)) > 0.0F) ++lit;
    }
    return lit;
  }

  // The summed RGB intensity of slot `slot` of every path.
  static glm::dvec3 slotSum(const Frame& frame, int slot) {
    glm::dvec3 sum(0.0);
    const lgh::VplLayout& layout = frame.probe.vplLayout;
    const auto paths = static_cast<std::size_t>(layout.paths);
    for (std::size_t p = 0; p < paths; ++p) {
      sum += glm::dvec3(
          glm::vec3(frame.probe.vpls[static_cast<std::size_t>(slot) * paths + p].intensityPad));
    }
    return sum;
  }

  static double meanLuminance(const lgh::FloatImage& image) {
    double sum = 0.0;
    const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
    for (std::size_t p = 0; p < pixels; ++p) {
      const float* c = &image.rgba[p * 4];
      sum += 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    }
    return sum / static_cast<double>(pixels);
  }

  static inline std::unique_ptr<lgh::GlContext> context;
  static inline std::unique_ptr<lgh::ShadowDevice> device;
  static inline std::unique_ptr<lgh::SceneCache> cache;
  static inline std::unique_ptr<lgh::FramePipeline> pipeline;
};

TEST_F(GlobalIllumination, VplCountLayoutAndDeterminism) {
  const json gi = {{"enabled", true}, {"bounces", 3}, {"vpl_count", 3001}, {"seed", 5}};
  const Frame first = renderDemo(gi);
  const Frame again = renderDemo(gi);
  json other = gi;
  other["seed"] = 6;
  const Frame reseeded = renderDemo(other);

  ASSERT_EQ(first.probe.vpls.size(), 3001U);
  const lgh::VplLayout& layout = first.probe.vplLayout;
  // The demo's ceiling panel emits: 3 bounces + its emission slot per path.
  EXPECT_TRUE(layout.emissionSlot);
  EXPECT_EQ(layout.slotsPerPath, 4);
  EXPECT_EQ(layout.paths, 750);
  EXPECT_EQ(first.report.decisions.at("vpl_source"), "light-paths");
  EXPECT_EQ(first.report.decisions.at("vpls"), "3001");
  EXPECT_EQ(first.report.decisions.at("gi_paths"), "750");
  // The slot left over and the emission slots of paths from analytic lights are dark; the rest
  // mostly lit (the room is open at the front, so some paths leave).
  EXPECT_EQ(glm::length(glm::vec3(first.probe.vpls.back().intensityPad)), 0.0F);
  const std::size_t lit = litVpls(first);
  std::cout << fmt::format("[ gi ] demo, 3 bounces: {} of 3001 VPLs lit\n", lit);
  EXPECT_GT(lit, 1500U);
  EXPECT_TRUE(sameVpls(first, again)) << "the same seed gives the same VPLs";
  EXPECT_FALSE(sameVpls(first, reseeded)) << "another seed, other VPLs";
  for (const lgh::PointLight& vpl : first.probe.vpls) {
    ASSERT_TRUE(std::isfinite(vpl.positionPad.x) && std::isfinite(vpl.intensityPad.r));
    ASSERT_GE(vpl.intensityPad.r, 0.0F);
  }
  for (const char* row : {"gi vpls", "gi emit", "gi bounce 1", "gi bounce 3", "gi rays",
                          "lgh build", "lgh lighting"}) {
    EXPECT_GE(first.report.timings.get(row), 0.0) << row;
  }
  // GL's wait for the light paths and their Vulkan timestamps are one row: the frame's GPU total
  // counts the generation once.
  EXPECT_EQ(std::count_if(first.report.timings.rows.begin(), first.report.timings.rows.end(),
                          [](const lgh::TimingRow& row) { return row.name == "gi vpls"; }),
            1);
}

TEST_F(GlobalIllumination, BothTracingPathsGiveTheSameVpls) {
  lgh::vk::ShadowTracer* tracer = device->tracer();
  ASSERT_NE(tracer, nullptr) << device->unavailableReason();
  if (!tracer->info().rayQuery || !tracer->info().rayTracingPipeline) {
    GTEST_SKIP() << "the Vulkan device lacks one of the paths";
  }
  const json gi = {{"enabled", true}, {"bounces", 3}, {"vpl_count", 6000}, {"seed", 11}};
  const Frame query = renderDemo(gi, "ray-query");
  const Frame pipelineFrame = renderDemo(gi, "pipeline");
  EXPECT_EQ(query.report.decisions.at("gi_tracing"), "ray-query");
  EXPECT_EQ(pipelineFrame.report.decisions.at("gi_tracing"), "pipeline");
  // The closest-hit batches go through lavapipe's memory pinned into GL
  // (shadows/batch_transport.hpp): llvmpipe cannot import lavapipe's memory, so interop is tried,
  // refused and logged first.
  EXPECT_EQ(query.report.decisions.at("gi_transport"), "pinned");
  EXPECT_EQ(pipelineFrame.report.decisions.at("gi_transport"), "pinned");
  EXPECT_TRUE(sameVpls(query, pipelineFrame));
  EXPECT_GT(litVpls(query), 3000U);
}

// In a closed room every light path hits a wall at every bounce and no path ends early, so the
// VPLs of bounce b carry the light's power x albedo^b / (2 pi) exactly (up to float sums): the
// light paths conserve energy. The frame's indirect light grows with the bounces by a factor that
// shrinks (a geometric series with ratio about the albedo).
TEST_F(GlobalIllumination, AClosedWhiteRoomConservesEnergyAndConverges) {
  constexpr float kAlbedo = 0.6F;
  constexpr float kIntensity = 2.0F;
  auto room = cached(closedRoom(kAlbedo));
  double previous = 0.0;
  double previousGain = 1e30;
  for (int bounces = 1; bounces <= 3; ++bounces) {
    json body = {{"output", {{"width", 40}, {"height", 30}}},
                 {"camera",
                  {{"type", "look_at"},
                   {"position", {0.0, 1.0, 0.9}},
                   {"target", {0.0, 1.0, -1.0}},
                   {"yfov", 90}}},
                 {"lights",
                  {{{"type", "point"}, {"position", {0.3, 1.4, -0.2}}, {"intensity", kIntensity}}}},
                 {"use_default_lights", false},
                 {"settings",
                  {{"shadows", "off"},
                   {"ambient", 0},
                   {"gi", {{"enabled", true}, {"bounces", bounces}, {"vpl_count", 3000}}}}}};
    const Frame frame = render(lgh::parseRenderRequest(body), *room);
    const lgh::VplLayout& layout = frame.probe.vplLayout;
    ASSERT_EQ(layout.slotsPerPath, bounces);
    ASSERT_EQ(layout.paths, 3000 / bounces);
    const double power = 4.0 * glm::pi<double>() * kIntensity;
    for (int b = 1; b <= bounces; ++b) {
      const glm::dvec3 sum = slotSum(frame, b - 1);
      const double expected = power * std::pow(kAlbedo, b) / (2.0 * glm::pi<double>());
      EXPECT_NEAR(sum.r / expected, 1.0, 1e-4) << "bounce " << b << " of " << bounces;
      EXPECT_NEAR(sum.g / expected, 1.0, 1e-4);
    }
    const double mean = meanLuminance(frame.probe.indirect);
    const double gain = mean - previous;
    std::cout << fmt::format("[ gi ] closed room, {} bounce(s): mean indirect {:.5f} (+{:.5f})\n",
                             bounces, mean, gain);
    EXPECT_GT(gain, 0.0) << "more bounces, more light";
    if (bounces > 1) EXPECT_LT(gain, previousGain) << "converging";
    previous = mean;
    previousGain = gain;
  }
}

// The light paths read the frame's materials (docs/MATERIALS.md): a request's `materials` that
// make the room's metal Phong clay colour the bounce's VPLs channel by channel, exactly as the
// energy check above predicts (a classic model's `diffuse` is all diffuse, whatever the metallic
// factor); the next request without them is back at the scene's own metal, which reflects no
// diffuse light.
TEST_F(GlobalIllumination, LightPathsReadTheRequestsMaterials) {
  constexpr float kIntensity = 2.0F;
  lgh::Scene metalRoom = closedRoom(0.6F);
  metalRoom.materials[0].metallicFactor = 1.0F;
  auto room = cached(std::move(metalRoom));
  const auto frameWith = [&](const json& materials) {
    json body = {{"output", {{"width", 24}, {"height", 18}}},
                 {"lights",
                  {{{"type", "point"}, {"position", {0.3, 1.4, -0.2}}, {"intensity", kIntensity}}}},
                 {"use_default_lights", false},
                 {"settings",
                  {{"shadows", "off"},
                   {"ambient", 0},
                   {"gi", {{"enabled", true}, {"bounces", 1}, {"vpl_count", 2000}}}}}};
    if (!materials.is_null()) body["materials"] = materials;
    return render(lgh::parseRenderRequest(body), *room);
  };
  const double power = 4.0 * glm::pi<double>() * kIntensity / (2.0 * glm::pi<double>());
  const glm::dvec3 diffuse(0.3, 0.45, 0.15);
  const Frame clay = frameWith(json::array(
      {{{"match", {{"index", 0}}},
        {"parameters", {{"model", "phong"}, {"diffuse", {diffuse.r, diffuse.g, diffuse.b}}}}}}));
  const glm::dvec3 sum = slotSum(clay, 0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(sum[c] / (power * diffuse[c]), 1.0, 1e-4) << "channel " << c;
  }
  const glm::dvec3 metal = slotSum(frameWith(json()), 0);
  EXPECT_EQ(metal, glm::dvec3(0.0)) << "the cached scene keeps its own (metal) material";
}

// The demo's ceiling panel (0.5 x 0.5, radiance (1, 0.95, 0.85), one-sided) is an area light: the
// emission VPLs of the paths that picked it sum to its power pi L A / (2 pi) (their share of all
// paths is its share of the power, in luminance).
TEST_F(GlobalIllumination, EmissiveTrianglesAreAreaLights) {
  const Frame frame = renderDemo({{"enabled", true}, {"bounces", 1}, {"vpl_count", 40000}});
  ASSERT_TRUE(frame.probe.vplLayout.emissionSlot);
  const glm::dvec3 emitted = slotSum(frame, 0);
  const double expected = glm::pi<double>() * 0.25 * 1.0 / (2.0 * glm::pi<double>());
  std::cout << fmt::format("[ gi ] demo panel: emission VPLs {:.4f}, expected {:.4f}\n", emitted.r,
                           expected);
  // Each path carries the same luminance of flux; the panel's share of paths is binomial.
  EXPECT_NEAR(emitted.r / expected, 1.0, 0.15);
  EXPECT_NEAR(emitted.g / emitted.r, 0.95, 1e-3);
}

void printErrors(const std::string& label, const lgh::MaterialErrors& e) {
  std::cout << fmt::format(
      "[ gi ] {}: relRMSE {:.4f} (diffuse {:.4f}, glossy {:.4f} on {:.1f}% of pixels), bias "
      "{:+.4f} (diffuse {:+.4f})\n",
      label, e.all.relativeRmse, e.diffuse.relativeRmse, e.glossy.relativeRmse,
      100.0 * e.glossyFraction, e.bias, e.diffuseBias);
}

// The shadowed frame's indirect light against both references on the demo: the brute force over
// the same VPLs (one shadow ray per VPL and pixel, no clamp; ground truth for the hierarchy and its
// sampled shadows) and the path tracer (ground truth for the VPLs themselves). The bounds are the
// documented behaviour (docs/GI.md, "Quality"): the VPLs' brightness matches the path tracer's
// closely here, and the frame's sampled shadows take some light away (merged grid lights whose
// centres sit in or behind objects).
TEST_F(GlobalIllumination, TheFrameAgainstBothReferences) {
  json body = {{"output", {{"width", 48}, {"height", 36}}},
               {"settings",
                {{"shadows", "on"},
                 {"ambient", 0},
                 {"lgh", {{"alpha", 2}, {"shadow_samples", 4}}},
                 {"gi", {{"enabled", true}, {"bounces", 2}, {"vpl_count", 8000}}}}}};
  Frame frame;
  frame.probe.bruteForce = true;
  frame.probe.shadowedReference = true;
  frame.probe.referenceClamp = lgh::LghFrameProbe::ReferenceClamp::Fixed;
  frame.probe.referenceMinDistance = 0.0F;
  frame.probe.pathTracedSamples = 128;
  const lgh::RenderRequest req = lgh::parseRenderRequest(body);
  lgh::gl::GpuTimer timer;
  pipeline->render(req, *cache->get(req.scene).entry, timer, frame.report, &frame.probe);
  const lgh::FloatImage shadowed = lgh::multiplied(frame.probe.indirect, frame.probe.shadowRatio);
  const auto& classes = frame.probe.metallicRoughness;
  const lgh::MaterialErrors toBruteForce =
      lgh::compareByMaterial(shadowed, frame.probe.reference, classes);
  const lgh::MaterialErrors toPathTracer =
      lgh::compareByMaterial(shadowed, frame.probe.pathTraced, classes);
  const lgh::MaterialErrors vplsToPathTracer =
      lgh::compareByMaterial(frame.probe.reference, frame.probe.pathTraced, classes);
  printErrors("LGH frame vs shadowed brute force", toBruteForce);
  printErrors("LGH frame vs path tracer", toPathTracer);
  printErrors("shadowed brute force vs path tracer", vplsToPathTracer);
  EXPECT_EQ(frame.report.decisions.at("reference"), "brute-force-shadowed");
  EXPECT_LT(std::fabs(vplsToPathTracer.bias), 0.15);
  EXPECT_LT(toBruteForce.bias, 0.0);
  EXPECT_GT(toBruteForce.bias, -0.35);
  EXPECT_LT(toBruteForce.diffuse.relativeRmse, 0.6);
}

// Inside a diffuse sphere every surface patch lights every other one alike (the form factor from
// a patch to a point of the sphere is the same everywhere), so with a point light at the centre
// the indirect irradiance after b bounces is uniform: E0 (rho + ... + rho^b), E0 = I / R^2, and the
// radiance everywhere rho / pi times that. Isotropic VPLs, too, give this in expectation (the
// sphere's 1/d potential), so both references must find it: the path tracer and the shadowed
// brute force over the VPLs (no clamp: here the singularity is integrable and VPLs are many).
TEST_F(GlobalIllumination, SphereRoomMatchesTheAnalyticRadiance) {
  constexpr float kAlbedo = 0.5F;
  constexpr float kIntensity = 3.0F;
  constexpr int kBounces = 2;
  auto room = cached(sphereRoom(kAlbedo, 48, 96));
  json body = {
      {"output", {{"width", 24}, {"height", 18}}},
      {"camera",
       {{"type", "look_at"},
        {"position", {0.0, 1.0, 0.3}},
        {"target", {0.0, 1.0, -1.0}},
        {"yfov", 70}}},
      {"lights", {{{"type", "point"}, {"position", {0.0, 1.0, 0.0}}, {"intensity", kIntensity}}}},
      {"use_default_lights", false},
      {"settings",
       {{"shadows", "on"},
        {"ambient", 0},
        {"gi", {{"enabled", true}, {"bounces", kBounces}, {"vpl_count", 12000}}}}}};
  Frame frame;
  frame.probe.bruteForce = true;
  frame.probe.shadowedReference = true;
  frame.probe.referenceClamp = lgh::LghFrameProbe::ReferenceClamp::Fixed;
  frame.probe.referenceMinDistance = 0.0F;
  frame.probe.pathTracedSamples = 128;
  lgh::gl::GpuTimer timer;
  pipeline->render(lgh::parseRenderRequest(body), *room, timer, frame.report, &frame.probe);
  double irradiance = 0.0;
  for (int b = 1; b <= kBounces; ++b) irradiance += kIntensity * std::pow(kAlbedo, b);
  const double expected = kAlbedo / glm::pi<double>() * irradiance;
  const double pathTraced = meanLuminance(frame.probe.pathTraced);
  const double bruteForce = meanLuminance(frame.probe.reference);
  const double lgh = meanLuminance(lgh::multiplied(frame.probe.indirect, frame.probe.shadowRatio));
  std::cout << fmt::format(
      "[ gi ] sphere room: expected {:.5f}, path traced {:.5f}, VPLs {:.5f}, "
      "LGH frame {:.5f} (unshadowed {:.5f}, shadow ratio {:.4f})\n",
      expected, pathTraced, bruteForce, lgh, meanLuminance(frame.probe.indirect),
      meanLuminance(frame.probe.shadowRatio));
  EXPECT_NEAR(pathTraced / expected, 1.0, 0.03);
  EXPECT_NEAR(bruteForce / expected, 1.0, 0.05);
  // Nothing occludes anything inside a sphere: the LGH's shadow samples must all get through.
  EXPECT_GT(meanLuminance(frame.probe.shadowRatio), 0.995);
}

// The hierarchy conserves energy: far from its lights (the VPLs a narrow spot leaves on the top of
// a small box, 10 m and more from every receiver), the LGH equals the brute force over the same
// VPLs within 1e-3, pixel by pixel (what remains is of second order in the box's size over the
// distance).
TEST_F(GlobalIllumination, FarFromItsLightsTheHierarchyEqualsTheBruteForce) {
  auto scene = cached(boxAboveFloor());
  json body = {{"output", {{"width", 48}, {"height", 32}}},
               {"camera",
                {{"type", "look_at"},
                 {"position", {0.0, 4.0, 16.0}},
                 {"target", {0.0, 0.0, 0.0}},
                 {"yfov", 60}}},
               {"lights",
                {{{"type", "spot"},
                  {"position", {0.0, 11.0, 0.0}},
                  {"direction", {0.0, -1.0, 0.0}},
                  {"intensity", 20000},
                  {"inner_cone_angle", 0.02},
                  {"outer_cone_angle", 0.08}}}},
               {"use_default_lights", false},
               {"settings",
                {{"shadows", "off"},
                 {"ambient", 0},
                 {"gi", {{"enabled", true}, {"bounces", 1}, {"vpl_count", 4000}}}}}};
  Frame frame;
  frame.probe.bruteForce = true;
  frame.probe.readGBuffer = true;
  frame.probe.readVpls = true;
  lgh::gl::GpuTimer timer;
  pipeline->render(lgh::parseRenderRequest(body), *scene, timer, frame.report, &frame.probe);
  ASSERT_GT(litVpls(frame), 900U) << "the spot's paths land on the box";
  double sumLgh = 0.0;
  double sumReference = 0.0;
  double worst = 0.0;
  int far = 0;
  for (std::size_t p = 0; p < frame.probe.gbuffer.position.size(); ++p) {
    const glm::vec4 position = frame.probe.gbuffer.position[p];
    if (position.w < 0.5F || glm::distance(glm::vec3(position), glm::vec3(0, 10, 0)) < 10.0F) {
      continue;
    }
    const float lgh = frame.probe.indirect.rgba[p * 4];
    const float reference = frame.probe.reference.rgba[p * 4];
    if (!(reference > 0.0F)) continue;
    sumLgh += lgh;
    sumReference += reference;
    worst = std::max(worst, std::fabs(static_cast<double>(lgh) / reference - 1.0));
    ++far;
  }
  std::cout << fmt::format(
      "[ gi ] far field ({} pixels): LGH / brute force {:.6f}, worst pixel "
      "{:.2e}\n",
      far, sumLgh / sumReference, worst);
  ASSERT_GT(far, 500);
  EXPECT_NEAR(sumLgh / sumReference, 1.0, 1e-3);
  EXPECT_LT(worst, 1e-3);
}

// Directional and spot lights deposit their power: over the floor of boxAboveFloor every path of a
// sun shining straight down hits (the box's top or the floor beneath the bounding box's top face),
// so the first bounce's VPLs carry albedo x E x the box's footprint / (2 pi); a spot pointing down
// at the floor, with its cone's edge a hard one (inner = outer), carries 2 pi (1 - cos outer) I.
TEST_F(GlobalIllumination, DirectionalAndSpotLightsDepositTheirPower) {
  constexpr double kAlbedo = 0.8;  // boxAboveFloor's white
  auto scene = cached(boxAboveFloor());
  const auto firstBounce = [&](const json& light) {
    json body = {{"output", {{"width", 32}, {"height", 24}}},
                 {"camera",
                  {{"type", "look_at"},
                   {"position", {0.0, 12.0, 30.0}},
                   {"target", {0.0, 0.0, 0.0}},
                   {"yfov", 60}}},
                 {"lights", {light}},
                 {"use_default_lights", false},
                 {"settings",
                  {{"shadows", "off"},
                   {"ambient", 0},
                   {"gi", {{"enabled", true}, {"bounces", 1}, {"vpl_count", 4000}}}}}};
    const Frame frame = render(lgh::parseRenderRequest(body), *scene);
    EXPECT_EQ(litVpls(frame), 4000U) << "every path hits";
    return slotSum(frame, 0);
  };
  constexpr double kSun = 3.0;
  const glm::dvec3 sun =
      firstBounce({{"type", "directional"}, {"direction", {0.0, -1.0, 0.0}}, {"intensity", kSun}});
  const double sunExpected = kAlbedo * kSun * 80.0 * 80.0 / (2.0 * glm::pi<double>());
  constexpr double kSpot = 50.0;
  constexpr double kOuter = 0.3;
  const glm::dvec3 spot = firstBounce({{"type", "spot"},
                                       {"position", {0.0, 5.0, 0.0}},
                                       {"direction", {0.0, -1.0, 0.0}},
                                       {"intensity", kSpot},
                                       {"inner_cone_angle", kOuter},
                                       {"outer_cone_angle", kOuter}});
  const double spotExpected = kAlbedo * kSpot * (1.0 - std::cos(kOuter));
  std::cout << fmt::format(
      "[ gi ] first bounce: sun {:.4f} (expected {:.4f}), spot {:.5f} ({:.5f})\n", sun.r,
      sunExpected, spot.r, spotExpected);
  EXPECT_NEAR(sun.r / sunExpected, 1.0, 1e-3);
  EXPECT_NEAR(sun.b / sunExpected, 1.0, 1e-3);
  // The hard edge is a ramp 1e-4 wide in cos(angle) (lights.glsl): under 0.3% of the cone.
  EXPECT_NEAR(spot.r / spotExpected, 1.0, 3e-3);
}

TEST_F(GlobalIllumination, ConflictingRequestsNameTheField) {
  const auto fails = [](const std::string& text, const std::string& field) {
    try {
      lgh::parseRenderRequest(text);
      ADD_FAILURE() << "parsed: " << text;
    } catch (const lgh::Error& error) {
      EXPECT_EQ(error.code(), lgh::ErrorCode::Invalid) << text;
      EXPECT_EQ(error.field(), field) << text;
    }
  };
  fails(R"({"settings": {"gi": {"enabled": true}, "lgh": {"vpl_count": 100}}})",
        "/settings/lgh/vpl_count");
  fails(R"({"settings": {"gi": {"enabled": true}, "lgh": {"enabled": false}}})",
        "/settings/lgh/enabled");
  const lgh::RenderRequest on =
      lgh::parseRenderRequest(R"({"settings": {"gi": {"enabled": true}}})");
  EXPECT_TRUE(on.settings.lgh.enabled);
  EXPECT_EQ(on.settings.gi.bounces, 3);
  EXPECT_EQ(on.settings.gi.vplCount, 100000);
}

// Each test runs in a process of its own (ctest): the Vulkan loader here finds no driver.
TEST(GlobalIlluminationWithoutVulkan, IsUnavailableNamingTheField) {
  setenv("VK_DRIVER_FILES", "/nonexistent/icd.json", 1);
  setenv("VK_ICD_FILENAMES", "/nonexistent/icd.json", 1);
  lgh::Renderer renderer(lgh::test::rendererOptions());
  try {
    renderer.render(lgh::parseRenderRequest(
        R"({"settings": {"gi": {"enabled": true, "vpl_count": 100}}, "output": {"width": 16, "height": 16}})"));
    FAIL() << "GI rendered without a Vulkan driver";
  } catch (const lgh::Error& error) {
    EXPECT_EQ(error.code(), lgh::ErrorCode::Unavailable);
    EXPECT_EQ(error.field(), "/settings/gi/enabled");
  }
  const lgh::RenderResult after =
      renderer.render(lgh::parseRenderRequest(R"({"output": {"width": 16, "height": 16}})"));
  EXPECT_EQ(after.pixels.width, 16);
}

}  // namespace
