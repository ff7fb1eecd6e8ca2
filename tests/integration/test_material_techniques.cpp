// The lecture's materials and texturing techniques, one golden image each, on llvmpipe: small
// procedural scenes (a brick board on the floor, a ball) rendered through the frame pipeline with
// the technique chosen by a request's `materials` (the same path as the daemon's and the CLI's).
// Goldens: tests/golden/technique_*.png (LGH_UPDATE_GOLDEN=1 to accept new ones, then look at
// them). Beside each golden a check that the technique does what it says (it changes the image
// where it should, holes are holes, compression saves memory).
//
// With LGH_GALLERY_DIR set, the same scenes are rendered larger and put side by side into the
// comparison strips of docs/GALLERY.md (scripts/material-gallery).
#include <gtest/gtest.h>

#include <random>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "context/gl_context.hpp"
#include "frame_pipeline.hpp"
#include "gl/software_rasterizer.hpp"
#include "lgh/testing/image_metrics.hpp"
#include "scene/procedural_textures.hpp"
#include "scene/scene_cache.hpp"
#include "scene/texture_upload.hpp"
#include "test_support.hpp"

namespace {

using json = nlohmann::json;

// Golden size, and the gallery's.
constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr int kGalleryWidth = 200;
constexpr int kGalleryHeight = 150;
// As the other goldens (tests/integration/test_render_golden.cpp).
constexpr double kMaxMeanError = 0.5;
constexpr double kMaxFraction = 0.002;

// Scene textures (Scene::textures, by index).
enum Texture {
  kBrickColor,
  kBrickHeight,
  kBrickNormal,
  kLightMap,
  kChecker,
  kHoles,
  kGloss,
};

lgh::Vertex vertex(const glm::vec3& position, const glm::vec3& normal, const glm::vec3& tangent,
                   const glm::vec2& uv) {
  lgh::Vertex v;
  v.position = position;
  v.normal = normal;
  v.tangent = glm::vec4(tangent, 1.0F);
  v.uv0 = uv;
  v.uv1 = uv;
  return v;
}

// A square on y = 0 facing up, u along +X, glTF's v along +Z (the image's top at the back), with
// `repeats` repeats of the texture.
lgh::Mesh board(float halfSize, float uvMin, float uvMax) {
  lgh::Primitive p;
  p.material = 0;
  p.tangents = true;
  const glm::vec3 up(0, 1, 0);
  const glm::vec3 x(1, 0, 0);
  p.vertices = {vertex({-halfSize, 0, halfSize}, up, x, {uvMin, uvMax}),
                vertex({halfSize, 0, halfSize}, up, x, {uvMax, uvMax}),
                vertex({halfSize, 0, -halfSize}, up, x, {uvMax, uvMin}),
                vertex({-halfSize, 0, -halfSize}, up, x, {uvMin, uvMin})};
  p.indices = {0, 1, 2, 0, 2, 3};
  return lgh::Mesh{"board", {p}, {}};
}

lgh::Mesh ball(int rings, int segments, int material) {
  lgh::Primitive p;
  p.material = material;
  p.tangents = true;
  for (int ring = 0; ring <= rings; ++ring) {
    const float theta = glm::pi<float>() * static_cast<float>(ring) / static_cast<float>(rings);
    for (int segment = 0; segment <= segments; ++segment) {
      const float phi =
          glm::two_pi<float>() * static_cast<float>(segment) / static_cast<float>(segments);
      const glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta),
                        std::sin(theta) * std::cos(phi));
      p.vertices.push_back(vertex(n * 0.3F, n, {std::cos(phi), 0.0F, -std::sin(phi)},
                                  {static_cast<float>(segment) / static_cast<float>(segments),
                                   static_cast<float>(ring) / static_cast<float>(rings)}));
    }
  }
  const auto stride = static_cast<std::uint32_t>(segments + 1);
  for (int ring = 0; ring < rings; ++ring) {
    for (int segment = 0; segment < segments; ++segment) {
      const std::uint32_t a = static_cast<std::uint32_t>(ring) * stride + segment;
      const std::uint32_t b = a + stride;
      if (ring != rings - 1) p.indices.insert(p.indices.end(), {a, b, b + 1});
      if (ring != 0) p.indices.insert(p.indices.end(), {a, b + 1, a + 1});
    }
  }
  return lgh::Mesh{"ball", {p}, {}};
}

lgh::LightDesc light(lgh::LightType type, const glm::vec3& position, const glm::vec3& direction,
                     float intensity) {
  lgh::LightDesc l;
  l.type = type;
  l.position = {position.x, position.y, position.z};
  const glm::vec3 d = glm::normalize(direction);
  l.direction = {d.x, d.y, d.z};
  l.intensity = intensity;
  return l;
}

// The scene every technique draws: a brick board on the floor (material 0, textured) with a
// ball behind it (material 1) that shows through blended and masked boards, a point light behind
// and above (its highlight lies on the board) and a low directional light from the left that
// makes relief cast shadows.
lgh::Scene techniqueScene(float uvMin = 0.0F, float uvMax = 2.0F) {
  lgh::Scene scene;
  scene.name = "techniques";
  const lgh::Image8 height = lgh::makeBrickHeightImage(128, 8);
  scene.images = {lgh::makeBrickColorImage(128, 8),      height,
                  lgh::makeNormalMapImage(height, 6.0F), lgh::makeLightMapImage(64),
                  lgh::makeCheckerImage(64, 8, 230, 40), lgh::makeHoleAlphaImage(128, 4),
                  lgh::makeCheckerImage(128, 4, 255, 40)};
  for (int i = 0; i < static_cast<int>(scene.images.size()); ++i) {
    lgh::TextureRef texture;
    texture.image = i;
    scene.textures.push_back(texture);
  }
  scene.meshes = {board(0.5F, uvMin, uvMax), ball(24, 48, 1)};
  scene.instances = {{0, glm::mat4(1.0F)},
                     {1, glm::translate(glm::mat4(1.0F), glm::vec3(0.1F, 0.0F, -0.9F))}};
  lgh::Material boardMaterial;
  boardMaterial.name = "board";
  boardMaterial.metallicFactor = 0.0F;
  boardMaterial.roughnessFactor = 0.7F;
  boardMaterial.baseColorTexture.image = kBrickColor;
  lgh::Material ballMaterial;
  ballMaterial.name = "ball";
  ballMaterial.baseColorFactor = glm::vec4(0.2F, 0.4F, 0.8F, 1.0F);
  ballMaterial.metallicFactor = 0.0F;
  ballMaterial.roughnessFactor = 0.4F;
  scene.materials = {boardMaterial, ballMaterial};
  scene.lights = {light(lgh::LightType::Point, {0.2F, 1.0F, -1.0F}, {0, -1, 0}, 2.5F),
                  light(lgh::LightType::Directional, {}, {1.0F, -0.45F, -0.3F}, 1.5F)};
  scene.computeBounds();
  return scene;
}

// A ball alone (rings x segments), for the illumination models and the shading modes, lit by a
// point light above and to the right of the camera and a dim fill.
lgh::Scene ballScene(int rings, int segments) {
  lgh::Scene scene;
  scene.name = "ball";
  scene.meshes = {ball(rings, segments, 0)};
  scene.instances = {{0, glm::mat4(1.0F)}};
  lgh::Material material;
  material.name = "ball";
  material.baseColorFactor = glm::vec4(0.75F, 0.42F, 0.25F, 1.0F);
  material.metallicFactor = 0.0F;
  material.roughnessFactor = 0.35F;
  scene.materials = {material};
  scene.lights = {light(lgh::LightType::Point, {0.8F, 0.9F, 1.2F}, {0, -1, 0}, 2.0F),
                  light(lgh::LightType::Directional, {}, {0.6F, 0.2F, -1.0F}, 0.3F)};
  scene.computeBounds();
  return scene;
}

const json kBoardCamera = {{"type", "look_at"},
                           {"position", {0.0, 0.5, 0.75}},
                           {"target", {0.0, 0.0, -0.1}},
                           {"yfov", 50}};
const json kBallCamera = {
    {"type", "look_at"}, {"position", {0.0, 0.0, 1.6}}, {"target", {0.0, 0.0, 0.0}}, {"yfov", 26}};

class MaterialTechniques : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context = lgh::GlContext::create(lgh::test::rendererOptions());
    pipeline = std::make_unique<lgh::FramePipeline>();
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &maxAnisotropy);
    board = upload(techniqueScene());
    smoothBall = upload(ballScene(24, 48));
    coarseBall = upload(ballScene(6, 12));
  }
  static void TearDownTestSuite() {
    board.reset();
    smoothBall.reset();
    coarseBall.reset();
    pipeline.reset();
    context.reset();
  }

  static std::shared_ptr<lgh::CachedScene> upload(
      lgh::Scene scene, lgh::TextureCompression compression = lgh::TextureCompression::None) {
    auto entry = std::make_shared<lgh::CachedScene>();
    entry->scene = std::move(scene);
    entry->gpu = std::make_unique<lgh::GpuScene>(entry->scene,
                                                 lgh::GpuSceneOptions{maxAnisotropy, compression});
    return entry;
  }

  struct Frame {
    lgh::Image8 image;
    lgh::FloatImage linear;
    lgh::FrameReport report;
  };

  // Renders `cached` with a request whose `materials` apply `parameters` to material `target`.
  static Frame render(const lgh::CachedScene& cached, const json& camera, const json& parameters,
                      int width = kWidth, int height = kHeight, const std::string& target = "",
                      bool depthPrepass = false) {
    json body = {
        {"camera", camera},
        {"output", {{"width", width}, {"height", height}, {"tone_map", "aces"}}},
        {"settings", {{"shadows", "off"}, {"ambient", 0.04}, {"depth_prepass", depthPrepass}}}};
    if (!parameters.empty()) {
      const json match = target.empty() ? json{{"index", 0}} : json{{"name", target}};
      body["materials"] = json::array({{{"match", match}, {"parameters", parameters}}});
    }
    const lgh::RenderRequest request = lgh::parseRenderRequest(body);
    Frame frame;
    lgh::gl::GpuTimer timer;
    pipeline->render(request, cached, timer, frame.report);
    frame.linear = frame.report.image;
    frame.image = lgh::toDisplay8(frame.linear, request.output.toneMap, 1.0F, false);
    return frame;
  }

  static Frame golden(const std::string& name, const lgh::CachedScene& cached, const json& camera,
                      const json& parameters) {
    Frame frame = render(cached, camera, parameters);
    EXPECT_EQ(lgh::test::checkGolden(frame.image, "technique_" + name, kMaxMeanError, kMaxFraction),
              "");
    return frame;
  }

  static inline std::unique_ptr<lgh::GlContext> context;
  static inline std::unique_ptr<lgh::FramePipeline> pipeline;
  static inline float maxAnisotropy = 1.0F;
  static inline std::shared_ptr<lgh::CachedScene> board;
  static inline std::shared_ptr<lgh::CachedScene> smoothBall;
  static inline std::shared_ptr<lgh::CachedScene> coarseBall;
};

// Mean absolute difference of two display images (0..255).
double difference(const lgh::Image8& a, const lgh::Image8& b) {
  return lgh::test::compareImages(a, b, 16).meanAbsoluteError;
}

// Pixels where nothing was drawn (the background colour, alpha as drawn).
int backgroundPixels(const lgh::FloatImage& image) {
  int count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.pixel(x, y);
      if (std::abs(p[0] - 0.02F) < 1e-4F && std::abs(p[2] - 0.025F) < 1e-4F) ++count;
    }
  }
  return count;
}

const json kHeightMap = {{"texture", kBrickHeight}};
const json kNormalMap = {{"texture", kBrickNormal}};

TEST_F(MaterialTechniques, IlluminationModels) {
  const std::vector<std::pair<std::string, json>> models = {
      {"model_metallic_roughness", json::object()},
      {"model_phong", {{"model", "phong"}, {"specular", {0.6, 0.6, 0.6}}, {"shininess", 40}}},
      // At Phong's exponent: the half vector's angle is about half the reflection's, so the
      // highlight is broader (the lecture's comparison).
      {"model_blinn_phong",
       {{"model", "blinn-phong"}, {"specular", {0.6, 0.6, 0.6}}, {"shininess", 40}}},
      {"model_lambert", {{"model", "oren-nayar"}, {"sigma", 0}}},
      {"model_oren_nayar", {{"model", "oren-nayar"}, {"sigma", 0.8}}},
      {"model_cook_torrance",
       {{"model", "cook-torrance"}, {"m", 0.15}, {"f0", {0.04, 0.04, 0.04}}}},
      {"model_cook_torrance_gold",
       {{"model", "cook-torrance"},
        {"diffuse", {0, 0, 0}},
        {"m", 0.25},
        {"f0", {1.0, 0.78, 0.34}}}},
  };
  std::vector<lgh::Image8> images;
  for (const auto& [name, parameters] : models) {
    SCOPED_TRACE(name);
    images.push_back(golden(name, *smoothBall, kBallCamera, parameters).image);
  }
  // Each model shows something else.
  for (std::size_t i = 0; i < images.size(); ++i) {
    for (std::size_t j = i + 1; j < images.size(); ++j) {
      EXPECT_GT(difference(images[i], images[j]), 0.2)
          << models[i].first << " vs " << models[j].first;
    }
  }
}

TEST_F(MaterialTechniques, ShadingModes) {
  const json phong = {{"model", "phong"}, {"specular", {0.7, 0.7, 0.7}}, {"shininess", 30}};
  std::vector<lgh::Image8> images;
  for (const char* mode : {"flat", "gouraud", "pixel"}) {
    SCOPED_TRACE(mode);
    json parameters = phong;
    parameters["shading"] = mode;
    images.push_back(
        golden(std::string("shading_") + mode, *coarseBall, kBallCamera, parameters).image);
  }
  EXPECT_GT(difference(images[0], images[1]), 1.0) << "flat vs Gouraud";
  EXPECT_GT(difference(images[1], images[2]), 0.3) << "Gouraud vs per pixel";
}

TEST_F(MaterialTechniques, SurfaceDetail) {
  const std::vector<std::pair<std::string, json>> techniques = {
      {"surface_texture", {{"surface", "none"}}},
      {"surface_normal", {{"surface", "normal"}, {"normal_texture", kNormalMap}}},
      {"surface_bump",
       {{"surface", "bump"}, {"height_texture", kHeightMap}, {"height_scale", 0.01}}},
      {"surface_parallax",
       {{"surface", "parallax"},
        {"height_texture", kHeightMap},
        {"normal_texture", kNormalMap},
        {"height_scale", 0.04}}},
      {"surface_relief",
       {{"surface", "relief"},
        {"height_texture", kHeightMap},
        {"normal_texture", kNormalMap},
        {"height_scale", 0.06}}},
      {"surface_displacement",
       {{"surface", "displacement"},
        {"height_texture", kHeightMap},
        {"height_scale", 0.03},
        {"tessellation_pixels", 2}}},
  };
  std::vector<Frame> frames;
  for (const auto& [name, parameters] : techniques) {
    SCOPED_TRACE(name);
    frames.push_back(golden(name, *board, kBoardCamera, parameters));
  }
  for (std::size_t i = 1; i < frames.size(); ++i) {
    EXPECT_GT(difference(frames[0].image, frames[i].image), 0.5) << techniques[i].first;
  }
  EXPECT_GT(difference(frames[3].image, frames[4].image), 0.5) << "relief vs parallax";
  EXPECT_EQ(frames[5].report.decisions.count("blended_surfaces"), 0U);
}

TEST_F(MaterialTechniques, ReliefSelfShadowAndSilhouettes) {
  const json relief = {
      {"surface", "relief"}, {"height_texture", kHeightMap}, {"height_scale", 0.08}};
  json unshadowed = relief;
  unshadowed["relief_self_shadow"] = false;
  const Frame shadowed = render(*board, kBoardCamera, relief);
  const Frame plain = render(*board, kBoardCamera, unshadowed);
  // Self-shadowing only takes light away.
  double darker = 0.0;
  for (std::size_t i = 0; i < shadowed.linear.rgba.size(); i += 4) {
    EXPECT_LE(shadowed.linear.rgba[i], plain.linear.rgba[i] + 1e-4F);
    darker += plain.linear.rgba[i] - shadowed.linear.rgba[i];
  }
  EXPECT_GT(darker, 1.0);
  // Silhouettes: the board's texture repeats twice; on one repeat (0..1) the march leaves the
  // square at its far edge, which cuts the outline.
  auto single = upload(techniqueScene(0.0F, 1.0F));
  json silhouettes = relief;
  silhouettes["relief_silhouettes"] = true;
  const Frame cut = golden("surface_relief_silhouettes", *single, kBoardCamera, silhouettes);
  const Frame whole = render(*single, kBoardCamera, relief);
  EXPECT_GT(backgroundPixels(cut.linear), backgroundPixels(whole.linear));
}

TEST_F(MaterialTechniques, MultiTexturing) {
  const Frame plain = render(*board, kBoardCamera, json::object());
  const Frame lightMap =
      golden("light_map", *board, kBoardCamera,
             {{"light_map", {{"texture", kLightMap}}}, {"light_map_strength", 1.5}});
  EXPECT_GT(difference(plain.image, lightMap.image), 2.0);
  const Frame maps = golden("gloss_specular_maps", *board, kBoardCamera,
                            {{"model", "blinn-phong"},
                             {"shininess", 200},
                             {"specular", {1, 1, 1}},
                             {"specular_texture", {{"texture", kChecker}}},
                             {"shininess_texture", {{"texture", kGloss}}}});
  EXPECT_GT(difference(plain.image, maps.image), 0.5);
  // Alpha test: the holes show the ball and the background behind the board.
  const json holes = {{"diffuse_texture", {{"texture", kHoles}}}};
  json mask = holes;
  mask["alpha_mode"] = "mask";
  json blend = holes;
  blend["alpha_mode"] = "blend";
  const Frame masked = golden("alpha_mask", *board, kBoardCamera, mask);
  const Frame blended = golden("alpha_blend", *board, kBoardCamera, blend);
  EXPECT_GT(backgroundPixels(masked.linear), backgroundPixels(plain.linear));
  EXPECT_EQ(blended.report.decisions.at("blended_surfaces"), "1");
  EXPECT_GT(difference(masked.image, blended.image), 0.5) << "soft edges and sorting";
}

TEST_F(MaterialTechniques, WrapModesAndFilters) {
  auto wide = upload(techniqueScene(-0.5F, 1.5F));
  json border = {{"diffuse_texture", {{"texture", kChecker}}},
                 {"sampling",
                  {{"wrap_s", "clamp-to-border"},
                   {"wrap_t", "mirrored-repeat"},
                   {"border_color", {0.9, 0.2, 0.1, 1.0}}}}};
  const Frame bordered = golden("wrap_border", *wide, kBoardCamera, border);
  // The border colour shows left and right of the texture.
  bool red = false;
  const auto channels = static_cast<std::size_t>(bordered.image.channels);
  for (std::size_t i = 0; i < bordered.image.pixels.size(); i += channels) {
    const auto* p = &bordered.image.pixels[i];
    red = red || (p[0] > 120 && p[1] < 70 && p[2] < 60);
  }
  EXPECT_TRUE(red);
  // Magnified: nearest shows the texels, bicubic smooths them.
  const json close = {{"type", "look_at"},
                      {"position", {0.0, 0.25, 0.2}},
                      {"target", {0.0, 0.0, 0.0}},
                      {"yfov", 30}};
  auto coarse = upload(techniqueScene(0.0F, 0.25F));
  const json checker = {{"diffuse_texture", {{"texture", kChecker}}}};
  json nearest = checker;
  nearest["sampling"] = {{"filter", "nearest"}};
  json bicubic = checker;
  bicubic["sampling"] = {{"filter", "bicubic"}};
  const Frame sharp = golden("filter_nearest", *coarse, close, nearest);
  const Frame smooth = golden("filter_bicubic", *coarse, close, bicubic);
  EXPECT_GT(difference(sharp.image, smooth.image), 1.0);
}

TEST_F(MaterialTechniques, CompressionOnUpload) {
  auto compressed = upload(techniqueScene(), lgh::TextureCompression::Bc);
  const json relief = {{"surface", "relief"},
                       {"height_texture", kHeightMap},
                       {"normal_texture", kNormalMap},
                       {"height_scale", 0.06}};
  const Frame plain = render(*board, kBoardCamera, relief);
  const Frame bc = golden("compression_bc", *compressed, kBoardCamera, relief);
  const lgh::GpuScene::TextureMemory memory = compressed->gpu->textureMemory();
  std::cout << fmt::format("bc: {} of {} textures compressed, {} bytes for {} as RGBA8 ({}); {}\n",
                           memory.compressed, memory.textures, memory.bytes,
                           memory.uncompressedBytes, bc.report.decisions.at("texture_memory"),
                           fmt::format("PSNR vs uncompressed {:.1f} dB",
                                       lgh::compareToReference(bc.linear, plain.linear).psnr));
  EXPECT_EQ(memory.compressed, memory.textures);
  // BC1 and BC4 take 1/8, BC3 and BC5 1/4 of RGBA8.
  EXPECT_LT(memory.bytes * 3, memory.uncompressedBytes);
  EXPECT_NE(bc.report.decisions.at("texture_memory").find("saved"), std::string::npos);
  EXPECT_GT(lgh::compareToReference(bc.linear, plain.linear).psnr, 30.0);
}

// A precompressed image with level 0 alone (a DDS file without mipmaps) gets the rest of the
// chain on upload: the 1 x 1 level holds the checker's mean (in linear light), not nothing.
TEST_F(MaterialTechniques, PrecompressedWithoutMipmapsGetsThem) {
  const lgh::Image8 checker = lgh::makeCheckerImage(64, 8, 235, 20);
  std::vector<std::string> warnings;
  const auto capabilities = lgh::TextureCapabilities::query();
  ASSERT_TRUE(capabilities.s3tc && capabilities.s3tcSrgb) << "llvmpipe has S3TC";
  // The driver's BC1 blocks of level 0, as a DDS file would hold them.
  const lgh::UploadedTexture source =
      lgh::uploadTexture(checker, nullptr, lgh::TextureUsage::Color, lgh::TextureCompression::Bc,
                         capabilities, warnings);
  lgh::BlockCompressedImage blocks;
  blocks.format = lgh::BlockFormat::Bc1;
  blocks.srgb = true;
  blocks.width = checker.width;
  blocks.height = checker.height;
  blocks.levels.emplace_back(lgh::blockLevelBytes(blocks.format, blocks.width, blocks.height));
  glGetCompressedTextureImage(source.texture.id(), 0,
                              static_cast<GLsizei>(blocks.levels.front().size()),
                              blocks.levels.front().data());
  const lgh::UploadedTexture loaded =
      lgh::uploadTexture(checker, &blocks, lgh::TextureUsage::Color, lgh::TextureCompression::None,
                         capabilities, warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  EXPECT_EQ(loaded.format, "BC1 sRGB");
  GLint levels = 0;
  glGetTextureParameteriv(loaded.texture.id(), GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
  EXPECT_EQ(levels, 7);
  std::array<std::uint8_t, 4> texel{};
  glGetTextureImage(loaded.texture.id(), 6, GL_RGBA, GL_UNSIGNED_BYTE, 4, texel.data());
  // (235 and 20 in sRGB) averaged in linear light, back in sRGB: 173; BC1 rounds to 5-6 bits.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(texel[static_cast<std::size_t>(c)], 173, 10) << c;
}

// Where the CPU builds the mip chains (a CPU rasteriser: TextureCapabilities::mipmapsOnCpu), they
// are the driver's own: llvmpipe's glGenerateMipmap gives the same bytes for data textures and
// the same codes within one for sRGB colour (its blit's sRGB encoding is an approximation; ours
// rounds exactly), at every level of a random texture.
TEST_F(MaterialTechniques, MipmapsBuiltOnTheCpuAreTheDriversOnACpuRasteriser) {
  if (!lgh::gl::softwareRasterizer()) GTEST_SKIP() << "the chains are built on the CPU there only";
  lgh::Image8 random;
  random.width = 64;
  random.height = 64;
  random.channels = 4;
  random.pixels.resize(std::size_t{64} * 64 * 4);
  std::mt19937 generator(11);
  for (std::uint8_t& code : random.pixels) code = static_cast<std::uint8_t>(generator());
  std::vector<std::string> warnings;
  for (const auto usage : {lgh::TextureUsage::Data, lgh::TextureUsage::Color}) {
    auto capabilities = lgh::TextureCapabilities::query();
    capabilities.mipmapsOnCpu = true;
    const lgh::UploadedTexture cpu = lgh::uploadTexture(
        random, nullptr, usage, lgh::TextureCompression::None, capabilities, warnings);
    capabilities.mipmapsOnCpu = false;
    const lgh::UploadedTexture driver = lgh::uploadTexture(
        random, nullptr, usage, lgh::TextureCompression::None, capabilities, warnings);
    const int tolerance = usage == lgh::TextureUsage::Data ? 0 : 1;
    for (int level = 1, size = 32; size >= 1; ++level, size /= 2) {
      std::vector<std::uint8_t> ours(static_cast<std::size_t>(size) * size * 4);
      std::vector<std::uint8_t> theirs(ours.size());
      glGetTextureImage(cpu.texture.id(), level, GL_RGBA, GL_UNSIGNED_BYTE,
                        static_cast<GLsizei>(ours.size()), ours.data());
      glGetTextureImage(driver.texture.id(), level, GL_RGBA, GL_UNSIGNED_BYTE,
                        static_cast<GLsizei>(theirs.size()), theirs.data());
      int largest = 0;
      for (std::size_t i = 0; i < ours.size(); ++i) {
        largest = std::max(largest, std::abs(int{ours[i]} - int{theirs[i]}));
      }
      EXPECT_LE(largest, tolerance) << "level " << level << (tolerance == 0 ? " data" : " sRGB");
    }
  }
}

// --- The gallery (docs/GALLERY.md) --------------------------------------------------------------

// Images side by side, 2 pixels of white between them.
lgh::Image8 strip(const std::vector<lgh::Image8>& images) {
  lgh::Image8 out;
  out.channels = images.front().channels;
  out.height = images.front().height;
  for (const auto& image : images) out.width += image.width + 2;
  out.width -= 2;
  const auto channels = static_cast<std::size_t>(out.channels);
  out.pixels.assign(static_cast<std::size_t>(out.width) * out.height * channels, 255);
  int left = 0;
  for (const auto& image : images) {
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        for (std::size_t c = 0; c < channels; ++c) {
          out.pixels[(static_cast<std::size_t>(y) * out.width + left + x) * channels + c] =
              image.pixels[(static_cast<std::size_t>(y) * image.width + x) * channels + c];
        }
      }
    }
    left += image.width + 2;
  }
  return out;
}

TEST_F(MaterialTechniques, Gallery) {
  const char* directory = std::getenv("LGH_GALLERY_DIR");
  if (directory == nullptr || *directory == '\0') GTEST_SKIP() << "LGH_GALLERY_DIR not set";
  const std::filesystem::path out(directory);
  std::filesystem::create_directories(out);
  auto save = [&](const std::string& name, const std::vector<lgh::Image8>& images) {
    lgh::image_io::writeFile(out / (name + ".png"), lgh::image_io::encodePng(strip(images)));
  };
  auto shot = [&](const lgh::CachedScene& scene, const json& camera, const json& parameters) {
    return render(scene, camera, parameters, kGalleryWidth, kGalleryHeight).image;
  };
  const json ballCamera = kBallCamera;
  save("models",
       {shot(*smoothBall, ballCamera, json::object()),
        shot(*smoothBall, ballCamera,
             {{"model", "phong"}, {"specular", {0.6, 0.6, 0.6}}, {"shininess", 40}}),
        shot(*smoothBall, ballCamera,
             {{"model", "blinn-phong"}, {"specular", {0.6, 0.6, 0.6}}, {"shininess", 40}}),
        shot(*smoothBall, ballCamera,
             {{"model", "blinn-phong"}, {"specular", {0.6, 0.6, 0.6}}, {"shininess", 160}}),
        shot(*smoothBall, ballCamera,
             {{"model", "cook-torrance"}, {"m", 0.15}, {"f0", {0.04, 0.04, 0.04}}}),
        shot(*smoothBall, ballCamera,
             {{"model", "cook-torrance"},
              {"diffuse", {0, 0, 0}},
              {"m", 0.25},
              {"f0", {1.0, 0.78, 0.34}}})});
  // Lambert against Oren-Nayar with the light behind the viewer: the rough ball looks flatter.
  auto frontLit = upload(ballScene(24, 48));
  frontLit->scene.lights = {light(lgh::LightType::Directional, {}, {0.0F, -0.1F, -1.0F}, 3.0F)};
  save("lambert_oren_nayar",
       {shot(*frontLit, ballCamera, {{"model", "oren-nayar"}, {"sigma", 0}}),
        shot(*frontLit, ballCamera, {{"model", "oren-nayar"}, {"sigma", 0.5}}),
        shot(*frontLit, ballCamera, {{"model", "oren-nayar"}, {"sigma", 1.0}})});
  const json phong = {{"model", "phong"}, {"specular", {0.7, 0.7, 0.7}}, {"shininess", 30}};
  std::vector<lgh::Image8> shading;
  for (const char* mode : {"flat", "gouraud", "pixel"}) {
    json parameters = phong;
    parameters["shading"] = mode;
    shading.push_back(shot(*coarseBall, ballCamera, parameters));
  }
  save("shading", shading);
  // The lecture's comparison: texture, normal, parallax and relief mapping; then bump and
  // displacement.
  save("surface",
       {shot(*board, kBoardCamera, {{"surface", "none"}}),
        shot(*board, kBoardCamera, {{"surface", "normal"}, {"normal_texture", kNormalMap}}),
        shot(*board, kBoardCamera,
             {{"surface", "parallax"},
              {"height_texture", kHeightMap},
              {"normal_texture", kNormalMap},
              {"height_scale", 0.04}}),
        shot(*board, kBoardCamera,
             {{"surface", "relief"},
              {"height_texture", kHeightMap},
              {"normal_texture", kNormalMap},
              {"height_scale", 0.06}})});
  // Relief mapping's self-shadowing, under the low light from the left alone.
  auto lowLight = upload(techniqueScene());
  lowLight->scene.lights.erase(lowLight->scene.lights.begin());
  const json relief = {
      {"surface", "relief"}, {"height_texture", kHeightMap}, {"height_scale", 0.06}};
  json unshadowed = relief;
  unshadowed["relief_self_shadow"] = false;
  save("relief_self_shadow",
       {shot(*lowLight, kBoardCamera, unshadowed), shot(*lowLight, kBoardCamera, relief)});
  save("surface_height",
       {shot(*board, kBoardCamera,
             {{"surface", "bump"}, {"height_texture", kHeightMap}, {"height_scale", 0.01}}),
        shot(*board, kBoardCamera,
             {{"surface", "displacement"},
              {"height_texture", kHeightMap},
              {"height_scale", 0.03},
              {"tessellation_pixels", 2}})});
  save("multitexturing",
       {shot(*board, kBoardCamera, json::object()),
        shot(*board, kBoardCamera,
             {{"light_map", {{"texture", kLightMap}}}, {"light_map_strength", 1.5}}),
        shot(*board, kBoardCamera,
             {{"model", "blinn-phong"},
              {"shininess", 200},
              {"specular", {1, 1, 1}},
              {"specular_texture", {{"texture", kChecker}}},
              {"shininess_texture", {{"texture", kGloss}}}}),
        shot(*board, kBoardCamera,
             {{"diffuse_texture", {{"texture", kHoles}}}, {"alpha_mode", "mask"}}),
        shot(*board, kBoardCamera,
             {{"diffuse_texture", {{"texture", kHoles}}}, {"alpha_mode", "blend"}})});
  auto wide = upload(techniqueScene(-0.5F, 1.5F));
  std::vector<lgh::Image8> wraps;
  for (const char* mode : {"repeat", "mirrored-repeat", "clamp-to-edge", "clamp-to-border"}) {
    wraps.push_back(
        shot(*wide, kBoardCamera,
             {{"diffuse_texture", {{"texture", kLightMap}}},
              {"sampling",
               {{"wrap_s", mode}, {"wrap_t", mode}, {"border_color", {0.1, 0.3, 0.8, 1}}}}}));
  }
  save("wrap_modes", wraps);
  std::cout << "gallery written to " << out << "\n";
}

// settings.depth_prepass draws the same image: the G-buffer's second draw passes the depth test
// (LEQUAL) exactly where the first draw left each pixel's nearest surface, for plain surfaces,
// relief mapping (whose silhouettes discard fragments) and tessellated displacement.
TEST_F(MaterialTechniques, DepthPrepassDrawsTheSameImage) {
  const std::vector<std::pair<std::string, json>> techniques = {
      {"plain", json::object()},
      {"relief",
       {{"surface", "relief"},
        {"height_texture", kHeightMap},
        {"normal_texture", kNormalMap},
        {"height_scale", 0.06}}},
      {"displacement",
       {{"surface", "displacement"},
        {"height_texture", kHeightMap},
        {"height_scale", 0.03},
        {"tessellation_pixels", 2}}},
  };
  for (const auto& [name, parameters] : techniques) {
    SCOPED_TRACE(name);
    const Frame once = render(*board, kBoardCamera, parameters);
    const Frame prepassed = render(*board, kBoardCamera, parameters, kWidth, kHeight, "", true);
    const lgh::test::ImageDifference difference =
        lgh::test::compareImages(prepassed.image, once.image, 0);
    EXPECT_EQ(difference.maxError, 0) << "mean " << difference.meanAbsoluteError;
  }
  const Frame ball = render(*smoothBall, kBallCamera, json::object());
  const Frame ballPrepassed =
      render(*smoothBall, kBallCamera, json::object(), kWidth, kHeight, "", true);
  EXPECT_EQ(lgh::test::compareImages(ballPrepassed.image, ball.image, 0).maxError, 0);
}

}  // namespace
