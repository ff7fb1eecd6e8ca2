// Material models and KHR_materials_* layers through every lighting path, on llvmpipe: a row of
// quads over a floor, one material each (plain, clearcoat, sheen, specular + ior, transmission,
// unlit), lit by a point light and 2000 VPLs. Checks:
//  - direct, LGH compute, LGH raster and the brute-force reference give finite images;
//  - the raster and compute LGH paths agree (relative RMSE <= 2e-3, as tests/integration/
//    test_lgh_lighting.cpp) and the LGH stays near the brute force (relative RMSE <= 0.35): all
//    of them evaluate the one BRDF of glsl/include/brdf.glsl;
//  - each layer changes what the plain material shows, and the unlit quad shows its base colour.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "context/gl_context.hpp"
#include "frame_pipeline.hpp"
#include "gl/shader_library.hpp"
#include "lgh/base64.hpp"
#include "lgh/testing/image_metrics.hpp"
#include "scene/camera.hpp"
#include "scene/scene_cache.hpp"
#include "test_support.hpp"

namespace {

using json = nlohmann::json;

constexpr int kWidth = 96;
constexpr int kHeight = 48;
constexpr int kQuads = 6;
enum Quad { Plain, Clearcoat, Sheen, Specular, Transmission, Unlit };
const glm::vec3 kUnlitColor(0.2F, 0.6F, 0.9F);

// A GLB: kQuads upright quads (x = i .. i + 0.8, y = 0.1 .. 0.9, facing +Z) over a floor.
std::vector<std::uint8_t> materialRowGlb() {
  std::vector<std::uint8_t> bin;
  json accessors = json::array();
  json views = json::array();
  json meshes = json::array();
  json nodes = json::array();
  auto addView = [&](const void* data, std::size_t size) {
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}});
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    bin.insert(bin.end(), bytes, bytes + size);
    return views.size() - 1;
  };
  auto addQuad = [&](glm::vec3 origin, glm::vec3 u, glm::vec3 v, int material) {
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    const std::vector<glm::vec3> corners = {origin, origin + u, origin + u + v, origin + v};
    std::vector<float> positions;
    std::vector<float> normals;
    glm::vec3 lo(1e9F);
    glm::vec3 hi(-1e9F);
    for (const glm::vec3& c : corners) {
      positions.insert(positions.end(), {c.x, c.y, c.z});
      normals.insert(normals.end(), {n.x, n.y, n.z});
      lo = glm::min(lo, c);
      hi = glm::max(hi, c);
    }
    const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
    accessors.push_back({{"bufferView", addView(positions.data(), 48)},
                         {"componentType", 5126},
                         {"count", 4},
                         {"type", "VEC3"},
                         {"min", {lo.x, lo.y, lo.z}},
                         {"max", {hi.x, hi.y, hi.z}}});
    accessors.push_back({{"bufferView", addView(normals.data(), 48)},
                         {"componentType", 5126},
                         {"count", 4},
                         {"type", "VEC3"}});
    accessors.push_back({{"bufferView", addView(indices.data(), 24)},
                         {"componentType", 5125},
                         {"count", 6},
                         {"type", "SCALAR"}});
    const std::size_t a = accessors.size() - 3;
    meshes.push_back({{"primitives",
                       {{{"attributes", {{"POSITION", a}, {"NORMAL", a + 1}}},
                         {"indices", a + 2},
                         {"material", material}}}}});
    nodes.push_back({{"mesh", meshes.size() - 1}});
  };
  for (int i = 0; i < kQuads; ++i) {
    addQuad({static_cast<float>(i), 0.1F, 0.0F}, {0.8F, 0, 0}, {0, 0.8F, 0}, i);
  }
  addQuad({-1, 0, 1.5F}, {kQuads + 1.0F, 0, 0}, {0, 0, -3.0F}, Plain);  // the floor, facing +Y
  const json base = {
      {"baseColorFactor", {0.7, 0.3, 0.2, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 0.5}};
  json materials = json::array();
  for (int i = 0; i < kQuads; ++i) materials.push_back({{"pbrMetallicRoughness", base}});
  materials[Clearcoat]["extensions"]["KHR_materials_clearcoat"] = {
      {"clearcoatFactor", 1}, {"clearcoatRoughnessFactor", 0.1}};
  materials[Sheen]["extensions"]["KHR_materials_sheen"] = {{"sheenColorFactor", {0.2, 0.9, 0.2}},
                                                           {"sheenRoughnessFactor", 1.0}};
  materials[Specular]["extensions"]["KHR_materials_specular"] = {
      {"specularFactor", 1}, {"specularColorFactor", {0.2, 0.2, 1}}};
  materials[Specular]["extensions"]["KHR_materials_ior"] = {{"ior", 2.5}};
  materials[Transmission]["extensions"]["KHR_materials_transmission"] = {
      {"transmissionFactor", 0.9}};
  materials[Unlit]["pbrMetallicRoughness"]["baseColorFactor"] = {kUnlitColor.r, kUnlitColor.g,
                                                                 kUnlitColor.b, 1};
  materials[Unlit]["extensions"]["KHR_materials_unlit"] = json::object();
  json sceneNodes = json::array();
  for (std::size_t i = 0; i < nodes.size(); ++i) sceneNodes.push_back(i);
  const json doc = {{"asset", {{"version", "2.0"}}},
                    {"extensionsUsed",
                     {"KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_specular",
                      "KHR_materials_ior", "KHR_materials_transmission", "KHR_materials_unlit"}},
                    {"scene", 0},
                    {"scenes", {{{"nodes", sceneNodes}}}},
                    {"nodes", nodes},
                    {"meshes", meshes},
                    {"materials", materials},
                    {"accessors", accessors},
                    {"bufferViews", views},
                    {"buffers", {{{"byteLength", bin.size()}}}}};
  std::string text = doc.dump();
  while (text.size() % 4 != 0) text.push_back(' ');
  while (bin.size() % 4 != 0) bin.push_back(0);
  std::vector<std::uint8_t> glb;
  auto put32 = [&glb](std::uint32_t value) {
    for (int b = 0; b < 4; ++b) glb.push_back(static_cast<std::uint8_t>(value >> (8 * b)));
  };
  put32(0x46546C67);
  put32(2);
  put32(static_cast<std::uint32_t>(28 + text.size() + bin.size()));
  put32(static_cast<std::uint32_t>(text.size()));
  put32(0x4E4F534A);
  glb.insert(glb.end(), text.begin(), text.end());
  put32(static_cast<std::uint32_t>(bin.size()));
  put32(0x004E4942);
  glb.insert(glb.end(), bin.begin(), bin.end());
  return glb;
}

class MaterialModels : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context = lgh::GlContext::create(lgh::test::rendererOptions());
    cache = std::make_unique<lgh::SceneCache>(lgh::RendererOptions{});
    pipeline = std::make_unique<lgh::FramePipeline>();
    glb = lgh::base64::encode(materialRowGlb());
  }
  static void TearDownTestSuite() {
    pipeline.reset();
    cache.reset();
    context.reset();
  }

  // path "none": direct lighting only (a directional light: every quad gets the same
  // irradiance, so the quads can be compared with each other).
  static lgh::RenderRequest request(const std::string& path) {
    json body = {
        {"scene", {{"glb_base64", glb}}},
        {"camera",
         {{"type", "look_at"},
          {"position", {2.9, 0.9, 5.2}},
          {"target", {2.9, 0.5, 0}},
          {"yfov", 36}}},
        {"lights", {{{"type", "directional"}, {"direction", {0.0, -0.4, -1.0}}, {"intensity", 2}}}},
        {"output", {{"width", kWidth}, {"height", kHeight}}},
        {"settings", {{"shadows", "off"}}}};
    if (path != "none") {
      body["settings"]["lgh"] = {
          {"enabled", true}, {"vpl_count", 2000}, {"seed", 3}, {"alpha", 4}, {"path", path}};
    }
    return lgh::parseRenderRequest(body);
  }

  struct Frame {
    lgh::FrameReport report;
    lgh::LghFrameProbe probe;
    lgh::CameraMatrices camera;
  };

  static Frame render(const std::string& path) {
    Frame frame;
    frame.probe.bruteForce = true;
    const lgh::RenderRequest req = request(path);
    const auto lookup = cache->get(req.scene);
    lgh::gl::GpuTimer timer;
    pipeline->render(req, *lookup.entry, timer, frame.report, &frame.probe);
    frame.camera = lgh::computeCamera(req.camera, lookup.entry->scene, kWidth, kHeight);
    return frame;
  }

  static inline std::unique_ptr<lgh::GlContext> context;
  static inline std::unique_ptr<lgh::SceneCache> cache;
  static inline std::unique_ptr<lgh::FramePipeline> pipeline;
  static inline std::string glb;
};

bool allFinite(const lgh::FloatImage& image) {
  for (float value : image.rgba) {
    if (!std::isfinite(value)) return false;
  }
  return !image.rgba.empty();
}

// The mean linear colour of `image` over the central 3x3 pixels of quad i.
glm::vec3 quadColor(const lgh::FloatImage& image, const lgh::CameraMatrices& camera, int quad) {
  const glm::vec4 clip = camera.viewProjection() * glm::vec4(quad + 0.4F, 0.5F, 0.0F, 1.0F);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  const int x = static_cast<int>((ndc.x * 0.5F + 0.5F) * kWidth);
  const int y = static_cast<int>((0.5F - ndc.y * 0.5F) * kHeight);  // top row first
  glm::vec3 sum(0.0F);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const float* p = image.pixel(x + dx, y + dy);
      sum += glm::vec3(p[0], p[1], p[2]);
    }
  }
  return sum / 9.0F;
}

TEST_F(MaterialModels, EveryPathShadesEveryModel) {
  const Frame compute = render("compute");
  const Frame raster = render("raster");
  EXPECT_EQ(compute.probe.path, lgh::LightingPath::Compute);
  EXPECT_EQ(raster.probe.path, lgh::LightingPath::Raster);
  EXPECT_TRUE(allFinite(compute.report.image));
  EXPECT_TRUE(allFinite(compute.probe.indirect));
  EXPECT_TRUE(allFinite(compute.probe.reference));
  EXPECT_TRUE(allFinite(raster.probe.indirect));
  const double paths =
      lgh::compareToReference(raster.probe.indirect, compute.probe.indirect).relativeRmse;
  EXPECT_LE(paths, 2e-3);
  const double hierarchy =
      lgh::compareToReference(compute.probe.indirect, compute.probe.reference).relativeRmse;
  EXPECT_LE(hierarchy, 0.35);
  std::cout << fmt::format("material models: raster vs compute {:.2e}, LGH vs brute force {:.3f}\n",
                           paths, hierarchy);
  const glm::vec3 unlitIndirect = quadColor(compute.probe.reference, compute.camera, Unlit);
  EXPECT_EQ(unlitIndirect, glm::vec3(0.0F));
}

TEST_F(MaterialModels, LayersChangeWhatTheSurfaceShows) {
  const Frame direct = render("none");
  const lgh::FloatImage& image = direct.report.image;
  const lgh::CameraMatrices& camera = direct.camera;
  const glm::vec3 plain = quadColor(image, camera, Plain);
  EXPECT_GT(plain.r, 0.0F);
  for (const Quad layered : {Clearcoat, Sheen, Specular, Transmission}) {
    const glm::vec3 color = quadColor(image, camera, layered);
    EXPECT_GT(glm::length(color - plain), 0.01F * glm::length(plain)) << "quad " << layered;
  }
  // Sheen adds a green lobe (and takes energy from the base: the green share grows); the blue
  // specular colour adds blue; the transmissive quad reflects less.
  const glm::vec3 sheen = quadColor(image, camera, Sheen);
  EXPECT_GT(sheen.g / sheen.r, plain.g / plain.r);
  EXPECT_GT(quadColor(image, camera, Specular).b, plain.b);
  EXPECT_LT(quadColor(image, camera, Transmission).r, plain.r);
  // Unlit: its base colour, whatever the light.
  const glm::vec3 unlit = quadColor(image, camera, Unlit);
  EXPECT_NEAR(unlit.r, kUnlitColor.r, 1e-3F);
  EXPECT_NEAR(unlit.g, kUnlitColor.g, 1e-3F);
  EXPECT_NEAR(unlit.b, kUnlitColor.b, 1e-3F);
}

// The shadow passes read the G-buffer too (readSurface), but need the Vulkan tracer to run: at
// least they must compile against the layered G-buffer here.
TEST_F(MaterialModels, ShadowPassShadersCompileWithTheLayeredGBuffer) {
  for (const char* shader : {"shadow_ray_setup.comp", "shadow_atrous.comp"}) {
    SCOPED_TRACE(shader);
    EXPECT_NE(lgh::gl::buildComputeProgram(shader).id(), 0U);
  }
}

}  // namespace
