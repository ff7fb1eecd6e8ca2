// The scene parser worker is invisible in the pictures: the glTF features of issue 20 (points and
// lines, KHR_texture_transform, Draco, meshopt, WebP, material layers and variants, skins and
// morph targets at a pose) render to the same pixels, with the same warnings, whether lghd parses
// assets in its worker (--scene-worker on, the default) or in its own process (off). Assets by
// path and an inline GLB, with the request's scene options (scene.animation,
// scene.material_variant), which must cross to the worker too, and an uploaded .gltf with side
// files; issue 22's materials: a glTF material whose extras.lgh asks for a classic model and bump
// mapping, textured by a DDS file (MSFT_texture_dds), with and without
// settings.texture_compression.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "daemon_process.hpp"
#include "gltf_quad.hpp"
#include "http_helpers.hpp"
#include "lgh/base64.hpp"

namespace lghd::test {
namespace {

namespace fs = std::filesystem;

class SceneWorkerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    withWorker = new DaemonProcess({"--scene-worker", "on"});
    inProcess = new DaemonProcess({"--scene-worker", "off"});
  }
  static void TearDownTestSuite() {
    delete withWorker;
    delete inProcess;
    withWorker = inProcess = nullptr;
  }
  void TearDown() override {
    if (HasFailure()) {
      std::cerr << "--- lghd (worker) log ---\n"
                << withWorker->log() << "--- lghd (in process) log ---\n"
                << inProcess->log();
    }
  }

  // Sends the same request to both daemons and checks they answer the same picture and warnings.
  template <typename Request>
  static void expectSame(const std::string& what, Request send) {
    SCOPED_TRACE(what);
    auto http1 = withWorker->client(std::chrono::seconds(300));
    auto http2 = inProcess->client(std::chrono::seconds(300));
    const httplib::Result a = send(*http1);
    const httplib::Result b = send(*http2);
    ASSERT_TRUE(a);
    ASSERT_TRUE(b);
    ASSERT_EQ(a->status, 200) << a->body;
    ASSERT_EQ(b->status, 200) << b->body;
    const auto imageA = decodeBody(a->body, what);
    const auto imageB = decodeBody(b->body, what);
    EXPECT_EQ(imageA.width, imageB.width);
    EXPECT_EQ(imageA.height, imageB.height);
    EXPECT_TRUE(imageA.pixels8 == imageB.pixels8) << "the pixels differ";
    EXPECT_EQ(a->get_header_value("X-Lgh-Warnings"), b->get_header_value("X-Lgh-Warnings"));
    int covered = 0;
    for (std::size_t i = 3; i < imageA.pixels8.size(); i += 4) {
      covered += imageA.pixels8[i] != 0 ? 1 : 0;
    }
    EXPECT_GT(covered, 0) << "nothing drawn: the comparison would prove little";
  }

  static json request(json scene) {
    return {
        {"scene", std::move(scene)},
        {"camera", {{"type", "auto"}}},
        {"output", {{"width", 48}, {"height", 48}, {"transparent_background", true}}},
        {"settings", {{"shadows", "off"}, {"primitives", {{"point_size", 5}, {"line_width", 2}}}}}};
  }

  static inline DaemonProcess* withWorker = nullptr;
  static inline DaemonProcess* inProcess = nullptr;
};

TEST_F(SceneWorkerTest, AssetsByPathRenderTheSame) {
  const json posed = {{"index", 0}, {"time", 1.5}};
  const std::vector<json> scenes = {
      {{"asset", "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf"}},
      {{"asset", "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_02.gltf"}},
      {{"asset", "textureTransform/TextureTransformTest.gltf"}},
      {{"asset", "draco/2CylinderEngine.gltf"}},
      {{"asset", "ClearCoat-glTF/ClearCoatTest.gltf"}},
      {{"asset", "simple_skin/simple_skin.gltf"}, {"animation", posed}},
      {{"asset", "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf"},
       {"animation", posed}}};
  for (const json& scene : scenes) {
    expectSame(scene.dump(),
               [&](httplib::Client& http) { return postJson(http, "/v1/render", request(scene)); });
  }
}

// tests/fuzz/seeds/gltf/compressed_features.glb: meshopt geometry, a WebP texture with a
// transform, material layers, a red variant, lines and points, a morph target, an animation.
TEST_F(SceneWorkerTest, InlineCompressedFeaturesRenderTheSame) {
  const std::string glb =
      readFile(fs::path(LGH_TEST_DATA_DIR) / "fuzz" / "seeds" / "gltf" / "compressed_features.glb");
  const std::string base64 = lgh::base64::encode(std::vector<std::uint8_t>(glb.begin(), glb.end()));
  const std::vector<json> scenes = {
      {{"glb_base64", base64}},
      {{"glb_base64", base64}, {"material_variant", "red"}},
      {{"glb_base64", base64}, {"animation", {{"index", 0}, {"time", 0.5}}}}};
  for (const json& scene : scenes) {
    std::string name = scene.dump();
    name.replace(name.find(base64), base64.size(), "...");
    expectSame(name,
               [&](httplib::Client& http) { return postJson(http, "/v1/render", request(scene)); });
  }
}

// An upload carries no scene options (scene beside files is a 400): Draco through side files.
TEST_F(SceneWorkerTest, UploadedGltfWithSideFilesRendersTheSame) {
  json plain = request(json::object());
  plain.erase("scene");
  expectSame("uploaded draco/2CylinderEngine.gltf", [&](httplib::Client& http) {
    return http.Post("/v1/render", httplib::MultipartFormDataItems{
                                       requestPart(plain), filePart("draco/2CylinderEngine.gltf"),
                                       filePart("draco/2CylinderEngine.bin")});
  });
}

// An 8 x 8 DXT1 DDS file (legacy header, one level): rows of red to green, so the height map
// (its red channel) slopes and bump mapping shows.
std::string gradientDds() {
  std::vector<std::uint8_t> file(128, 0);
  auto put32 = [&file](std::size_t offset, std::uint32_t value) {
    for (std::size_t i = 0; i < 4; ++i) {
      file[offset + i] = static_cast<std::uint8_t>(value >> (8 * i));
    }
  };
  file[0] = 'D';
  file[1] = 'D';
  file[2] = 'S';
  file[3] = ' ';
  put32(4, 124);
  put32(8, 0x1 | 0x2 | 0x4 | 0x1000 | 0x80000);  // caps, height, width, pixel format, linear size
  put32(12, 8);                                  // height
  put32(16, 8);                                  // width
  put32(20, 32);                                 // bytes of level 0
  put32(28, 1);                                  // mip levels
  put32(76, 32);                                 // pixel format size
  put32(80, 0x4);                                // FourCC
  file[84] = 'D';
  file[85] = 'X';
  file[86] = 'T';
  file[87] = '1';
  put32(108, 0x1000);  // a texture
  for (int block = 0; block < 4; ++block) {
    // colour 0 red, colour 1 green (colour 0 > colour 1: four colours); rows 0, 2, 3, 1.
    const std::uint8_t bytes[8] = {0x00, 0xF8, 0xE0, 0x07, 0x00, 0xAA, 0xFF, 0x55};
    file.insert(file.end(), bytes, bytes + 8);
  }
  return {file.begin(), file.end()};
}

// A quad whose material is the lecture's Blinn-Phong with bump mapping (glTF extras.lgh), its
// base colour and height map the DDS file.
std::vector<httplib::MultipartFormData> lectureQuadFiles() {
  const json extras = {{"lgh",
                        {{"model", "blinn-phong"},
                         {"shininess", 24},
                         {"surface", "bump"},
                         {"height_texture", {{"texture", 0}}},
                         {"height_scale", 0.05}}}};
  const lgh::test::GltfQuad quad = lgh::test::ddsTexturedQuad("lecture", "gradient.dds", extras);
  const std::string bin(quad.bin.begin(), quad.bin.end());
  return {{"file", quad.gltf, "quad.gltf", "model/gltf+json"},
          {"file", bin, "quad.bin", "application/octet-stream"},
          {"file", gradientDds(), "gradient.dds", "image/vnd-ms.dds"}};
}

TEST_F(SceneWorkerTest, LectureMaterialWithDdsTextureRendersTheSame) {
  for (const char* compression : {"none", "bc"}) {
    json plain = request(json::object());
    plain.erase("scene");
    plain["settings"]["texture_compression"] = compression;
    expectSame(std::string("classic model, bump, DDS; texture_compression ") + compression,
               [&](httplib::Client& http) {
                 httplib::MultipartFormDataItems items{requestPart(plain)};
                 for (auto& file : lectureQuadFiles()) items.push_back(std::move(file));
                 return http.Post("/v1/render", items);
               });
  }
}

}  // namespace
}  // namespace lghd::test
