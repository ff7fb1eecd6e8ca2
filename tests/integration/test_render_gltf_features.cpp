// Golden images of the glTF features of issue 20, one asset each, small, rendered on llvmpipe:
// points, lines, KHR_texture_transform, KHR_draco_mesh_compression, EXT_meshopt_compression (a GLB
// made here), a skinned pose, a morph weight and KHR_materials_clearcoat. Metric and thresholds
// as test_render_golden.cpp (lgh::test::checkGolden, docs/TESTING.md).
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "lgh/base64.hpp"
#include "lgh/renderer.hpp"
#include "test_support.hpp"

namespace {

using json = nlohmann::json;

constexpr double kMaxMeanError = 0.5;
constexpr double kMaxFraction = 0.002;

class GltfFeatureGolden : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    lgh::RendererOptions options = lgh::test::rendererOptions();
    options.assetRoot = lgh::test::assimpGltfDir();
    renderer = std::make_unique<lgh::Renderer>(options);
  }
  static void TearDownTestSuite() { renderer.reset(); }

  // Renders `request` (shadows off: the goldens are about the G-buffer and shading) and checks it.
  static std::string golden(json request, const std::string& name) {
    request["settings"]["shadows"] = "off";
    const lgh::RenderRequest parsed = lgh::parseRenderRequest(request);
    const lgh::Image8 image = renderer->render(parsed).pixels.toImage8();
    return lgh::test::checkGolden(image, name, kMaxMeanError, kMaxFraction);
  }

  static json asset(const std::string& path, int width, int height) {
    return {{"scene", {{"asset", path}}},
            {"camera", {{"type", "auto"}}},
            {"output", {{"width", width}, {"height", height}}}};
  }

  static inline std::unique_ptr<lgh::Renderer> renderer;
};

const std::string kPrimitiveModes = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_";

TEST_F(GltfFeatureGolden, Points) {
  json request = asset(kPrimitiveModes + "00.gltf", 64, 64);
  request["settings"]["primitives"] = {{"point_size", 6}, {"point_shape", "disk"}};
  EXPECT_EQ(golden(request, "gltf_points_64"), "");
}

TEST_F(GltfFeatureGolden, LineLoop) {
  json request = asset(kPrimitiveModes + "02.gltf", 64, 64);
  request["settings"]["primitives"] = {{"line_width", 3}};
  EXPECT_EQ(golden(request, "gltf_line_loop_64"), "");
}

TEST_F(GltfFeatureGolden, TextureTransform) {
  json request = asset("textureTransform/TextureTransformTest.gltf", 128, 96);
  request["camera"] = {{"type", "auto"}, {"view_direction", {0, 0, 1}}};
  EXPECT_EQ(golden(request, "gltf_texture_transform_128x96"), "");
}

TEST_F(GltfFeatureGolden, Draco) {
  json request = asset("draco/2CylinderEngine.gltf", 96, 72);
  request["camera"]["view_direction"] = {1, 0.5, 1};
  EXPECT_EQ(golden(request, "gltf_draco_96x72"), "");
}

TEST_F(GltfFeatureGolden, SkinnedPose) {
  json request = asset("simple_skin/simple_skin.gltf", 64, 64);
  request["scene"]["animation"] = {{"index", 0}, {"time", 2.0}};
  request["camera"]["view_direction"] = {0, 0, 1};
  EXPECT_EQ(golden(request, "gltf_skin_pose_64"), "");
}

TEST_F(GltfFeatureGolden, MorphWeight) {
  json request = asset("glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf", 64, 64);
  request["scene"]["animation"] = {{"index", 0}, {"time", 1.5}};
  EXPECT_EQ(golden(request, "gltf_morph_weight_64"), "");
}

TEST_F(GltfFeatureGolden, Clearcoat) {
  json request = asset("ClearCoat-glTF/ClearCoatTest.gltf", 128, 96);
  request["camera"] = {{"type", "auto"}, {"view_direction", {0, 0, 1}}};
  EXPECT_EQ(golden(request, "gltf_clearcoat_128x96"), "");
}

// A GLB whose geometry is EXT_meshopt_compression-encoded: a tetrahedron with vertex colours.
std::vector<std::uint8_t> meshoptTetrahedronGlb() {
  struct Vertex {
    float position[3];
    float color[4];
  };
  const std::vector<Vertex> vertices = {{{0, 1, 0}, {1, 0.2F, 0.2F, 1}},
                                        {{-1, -0.6F, 0.6F}, {0.2F, 1, 0.2F, 1}},
                                        {{1, -0.6F, 0.6F}, {0.2F, 0.2F, 1, 1}},
                                        {{0, -0.6F, -1}, {1, 1, 0.2F, 1}}};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};
  std::vector<unsigned char> vertexStream(meshopt_encodeVertexBufferBound(4, sizeof(Vertex)));
  vertexStream.resize(meshopt_encodeVertexBuffer(vertexStream.data(), vertexStream.size(),
                                                 vertices.data(), 4, sizeof(Vertex)));
  std::vector<unsigned char> indexStream(meshopt_encodeIndexBufferBound(12, 4));
  indexStream.resize(
      meshopt_encodeIndexBuffer(indexStream.data(), indexStream.size(), indices.data(), 12));
  std::vector<std::uint8_t> bin(vertexStream.begin(), vertexStream.end());
  while (bin.size() % 4 != 0) bin.push_back(0);
  const std::size_t indexOffset = bin.size();
  bin.insert(bin.end(), indexStream.begin(), indexStream.end());
  while (bin.size() % 4 != 0) bin.push_back(0);
  const std::size_t vertexBytes = 4 * sizeof(Vertex);
  const json doc = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"EXT_meshopt_compression"}},
      {"extensionsRequired", {"EXT_meshopt_compression"}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"COLOR_0", 1}}}, {"indices", 2}}}}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", 4},
         {"type", "VEC3"},
         {"min", {-1, -0.6, -1}},
         {"max", {1, 1, 0.6}}},
        {{"bufferView", 0},
         {"byteOffset", 12},
         {"componentType", 5126},
         {"count", 4},
         {"type", "VEC4"}},
        {{"bufferView", 1}, {"componentType", 5125}, {"count", 12}, {"type", "SCALAR"}}}},
      // The views' own buffer (1) is the fallback: no data, only the compressed buffer 0 has.
      {"bufferViews",
       {{{"buffer", 1},
         {"byteLength", vertexBytes},
         {"byteStride", sizeof(Vertex)},
         {"extensions",
          {{"EXT_meshopt_compression",
            {{"buffer", 0},
             {"byteOffset", 0},
             {"byteLength", vertexStream.size()},
             {"byteStride", sizeof(Vertex)},
             {"count", 4},
             {"mode", "ATTRIBUTES"}}}}}},
        {{"buffer", 1},
         {"byteOffset", vertexBytes},
         {"byteLength", 48},
         {"extensions",
          {{"EXT_meshopt_compression",
            {{"buffer", 0},
             {"byteOffset", indexOffset},
             {"byteLength", indexStream.size()},
             {"byteStride", 4},
             {"count", 12},
             {"mode", "TRIANGLES"}}}}}}}},
      {"buffers",
       {{{"byteLength", bin.size()}},
        {{"byteLength", vertexBytes + 48},
         {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}}};
  std::string text = doc.dump();
  while (text.size() % 4 != 0) text.push_back(' ');
  std::vector<std::uint8_t> glb;
  auto put32 = [&glb](std::uint32_t value) {
    for (int b = 0; b < 4; ++b) glb.push_back(static_cast<std::uint8_t>(value >> (8 * b)));
  };
  put32(0x46546C67);
  put32(2);
  put32(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
  put32(static_cast<std::uint32_t>(text.size()));
  put32(0x4E4F534A);
  glb.insert(glb.end(), text.begin(), text.end());
  put32(static_cast<std::uint32_t>(bin.size()));
  put32(0x004E4942);
  glb.insert(glb.end(), bin.begin(), bin.end());
  return glb;
}

TEST_F(GltfFeatureGolden, Meshopt) {
  const std::vector<std::uint8_t> glb = meshoptTetrahedronGlb();
  const json request = {{"scene", {{"glb_base64", lgh::base64::encode(glb)}}},
                        {"camera", {{"type", "auto"}, {"view_direction", {0.3, 0.4, 1}}}},
                        {"output", {{"width", 64}, {"height", 64}}}};
  EXPECT_EQ(golden(request, "gltf_meshopt_64"), "");
}

}  // namespace
