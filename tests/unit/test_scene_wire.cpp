// The scene parser worker's messages (scene/worker/scene_wire): a scene crosses the process
// boundary whole (every field the renderer reads, the glTF features of issue 20 included: line and
// point lists, texture transforms, material models and layers; issue 22's classic models, surface
// detail, light maps, bicubic filtering, border colours, anisotropy, tangent flags, DDS block
// payloads and the textures list), a load job carries the request's
// scene options, and the daemon's side refuses a message whose values would make the renderer
// read out of range or switch on an unknown value.
#include <array>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lgh/error.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/scene.hpp"
#include "scene/worker/scene_wire.hpp"
#include "scene_compare.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using lgh::Error;
using lgh::ErrorCode;
using lgh::Scene;
using lgh::test::expectSameScene;

std::vector<std::uint8_t> bytesOf(const lgh::worker::Encoded& encoded) {
  std::vector<std::uint8_t> bytes(encoded.size);
  encoded.write(bytes.data());
  return bytes;
}

Scene roundTrip(const Scene& scene) {
  const lgh::worker::LoadOutcome outcome = scene;
  const std::vector<std::uint8_t> bytes = bytesOf(lgh::worker::encodeOutcome(outcome));
  lgh::worker::LoadOutcome decoded = lgh::worker::decodeOutcome(bytes);
  return std::get<Scene>(std::move(decoded));
}

// The daemon's side of a scene the worker sent: the error it throws, or Internal "accepted".
Error refusal(const Scene& scene) {
  try {
    roundTrip(scene);
  } catch (const Error& error) {
    return error;
  }
  return Error(ErrorCode::Internal, "accepted");
}

lgh::Primitive primitive(lgh::Topology topology, std::vector<std::uint32_t> indices, int material) {
  lgh::Primitive p;
  p.topology = topology;
  p.indices = std::move(indices);
  p.vertices.resize(4);
  for (std::size_t i = 0; i < p.vertices.size(); ++i) {
    p.vertices[i].position = glm::vec3(static_cast<float>(i), 1.0F, -2.0F);
    p.vertices[i].uv1 = glm::vec2(0.5F, static_cast<float>(i));
  }
  p.material = material;
  p.unlit = topology != lgh::Topology::Triangles;
  p.tangents = topology == lgh::Topology::Triangles;
  return p;
}

// A scene with every field off its default, main's glTF features included.
Scene everyField() {
  Scene scene;
  scene.name = "every field";
  lgh::Mesh mesh;
  mesh.name = "mixed";
  mesh.primitives.push_back(primitive(lgh::Topology::Triangles, {0, 1, 2, 2, 3, 0}, 0));
  mesh.linesAndPoints.push_back(primitive(lgh::Topology::Lines, {0, 1, 1, 2}, 1));
  mesh.linesAndPoints.push_back(primitive(lgh::Topology::Points, {0, 2, 3}, -1));
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, glm::mat4(2.0F)});
  lgh::Material layered;
  layered.name = "layered";
  layered.baseColorFactor = {0.1F, 0.2F, 0.3F, 0.4F};
  layered.alphaMode = lgh::AlphaMode::Mask;
  layered.doubleSided = true;
  layered.clearcoat = {0.7F, 0.2F, {}, {}, {}, 0.9F};
  layered.sheen.colorFactor = {0.3F, 0.2F, 0.9F};
  layered.sheen.roughnessFactor = 0.4F;
  layered.specular.factor = 0.8F;
  layered.specular.colorFactor = {1.0F, 0.9F, 0.8F};
  layered.specular.ior = 1.4F;
  layered.transmission.factor = 0.3F;
  layered.transmission.thicknessFactor = 0.5F;
  layered.transmission.attenuationColor = {0.9F, 0.6F, 0.5F};
  layered.transmission.attenuationDistance = 2.0F;
  // Each texture slot names the image and a transform of its own.
  lgh::Material& m = layered;
  const std::array textures{
      &m.baseColorTexture,           &m.metallicRoughnessTexture, &m.normalTexture,
      &m.occlusionTexture,           &m.emissiveTexture,          &m.clearcoat.texture,
      &m.clearcoat.roughnessTexture, &m.clearcoat.normalTexture,  &m.sheen.colorTexture,
      &m.sheen.roughnessTexture,     &m.specular.texture,         &m.specular.colorTexture,
      &m.transmission.texture,       &m.surface.heightTexture,    &m.lightMap};
  for (std::size_t i = 0; i < textures.size(); ++i) {
    lgh::TextureRef& texture = *textures[i];
    texture.image = 0;
    texture.texCoord = static_cast<int>(i % 2);
    texture.sampler.wrapS = 0x812D;  // GL_CLAMP_TO_BORDER
    texture.sampler.borderColor = {0.25F, 0.5F, 0.75F, 1.0F};
    texture.sampler.anisotropy = static_cast<float>(i + 1);
    texture.transform.offset = {0.01F * static_cast<float>(i), 0.5F};
    texture.transform.rotation = 0.1F * static_cast<float>(i);
    texture.transform.scale = {2.0F, 3.0F};
  }
  layered.surface.technique = lgh::SurfaceDetail::Relief;
  layered.surface.heightScale = 0.125F;
  layered.surface.parallaxBias = -0.0625F;
  layered.surface.reliefLinearSteps = 17;
  layered.surface.reliefBinarySteps = 3;
  layered.surface.reliefSelfShadow = false;
  layered.surface.reliefSilhouettes = true;
  layered.surface.tessellationPixels = 12.0F;
  layered.surface.tessellationMaxLevel = 9;
  layered.lightMapStrength = 0.75F;
  layered.bicubic = true;
  lgh::Material unlit;
  unlit.name = "unlit";
  unlit.model = lgh::MaterialModel::Unlit;
  // The lecture's classic model, with its own specular and gloss maps in slots 10 and 11.
  lgh::Material classic;
  classic.name = "classic";
  classic.model = lgh::MaterialModel::CookTorrance;
  classic.classic.ambient = glm::vec3(0.1F, 0.2F, 0.3F);
  classic.classic.specular = {0.6F, 0.5F, 0.4F};
  classic.classic.shininess = 12.0F;
  classic.classic.sigma = 0.2F;
  classic.classic.m = 0.45F;
  classic.classic.f0 = {0.9F, 0.6F, 0.3F};
  classic.classic.shading = lgh::ShadingMode::Gouraud;
  classic.classic.specularTexture.image = 1;
  classic.classic.specularTexture.sampler.anisotropy = 4.0F;
  classic.classic.shininessTexture.image = 0;
  classic.classic.shininessTexture.texCoord = 1;
  scene.materials = {layered, unlit, classic};
  lgh::Image8 image;
  image.width = 2;
  image.height = 1;
  image.pixels = {1, 2, 3, 4, 5, 6, 7, 8};
  scene.images.push_back(image);
  // A DDS image: its decoded pixels and its BC1 blocks (one 4x4 block per level: 4x4, 2x2, 1x1).
  lgh::BlockCompressedImage blocks;
  blocks.format = lgh::BlockFormat::Bc1;
  blocks.srgb = true;
  blocks.width = 4;
  blocks.height = 4;
  for (std::uint8_t level = 0; level < 3; ++level) {
    blocks.levels.push_back({level, 1, 2, 3, 4, 5, 6, 7});
  }
  scene.images.push_back(lgh::decodeBlocks(blocks.format, 4, 4, blocks.levels[0].data()));
  scene.compressedImages.emplace(1, blocks);
  scene.textures = {m.baseColorTexture, classic.classic.specularTexture};
  lgh::LightDesc light;
  light.intensity = 3.0F;
  light.radius = 0.25F;
  scene.lights.push_back(light);
  lgh::SceneCamera camera;
  camera.name = "camera";
  camera.yfov = 0.5F;
  scene.cameras.push_back(camera);
  scene.warnings = {"a warning"};
  scene.computeBounds();
  return scene;
}

TEST(SceneWire, EveryFieldCrosses) {
  const Scene scene = everyField();
  ASSERT_TRUE(scene.materials[0].hasLayers());
  expectSameScene(scene, roundTrip(scene));
}

// Loaded scenes with issue 20's features: the compressed-features seed (meshopt, WebP, texture
// transform, material layers, lines and points, a morph target) in its default, red variant and
// animated poses; Draco; a posed skin.
TEST(SceneWire, LoadedFeatureScenesCross) {
  const fs::path seeds = lgh::test::dataDir() / "fuzz" / "seeds" / "gltf";
  lgh::SceneLoadOptions posed;
  posed.animation = lgh::SceneAnimation{0, 0.5F};
  lgh::SceneLoadOptions red;
  red.materialVariant = "red";
  for (const lgh::SceneLoadOptions& options : {lgh::SceneLoadOptions{}, posed, red}) {
    const Scene scene =
        lgh::loadGltfFile(seeds, "compressed_features.glb", lgh::SceneLoadLimits{}, options);
    ASSERT_EQ(scene.meshes.size(), 1U);
    EXPECT_EQ(scene.meshes[0].linesAndPoints.size(), 2U);
    EXPECT_EQ(scene.images.size(), 1U);
    expectSameScene(scene, roundTrip(scene));
  }
  const fs::path models = lgh::test::assimpGltfDir();
  expectSameScene(lgh::loadGltfFile(models, "draco/2CylinderEngine.gltf"),
                  roundTrip(lgh::loadGltfFile(models, "draco/2CylinderEngine.gltf")));
  const Scene skin = lgh::loadGltfFile(models, "simple_skin/simple_skin.gltf", {}, posed);
  expectSameScene(skin, roundTrip(skin));
}

TEST(SceneWire, JobsCarryTheSceneOptions) {
  lgh::worker::LoadJob job;
  job.source.kind = lgh::SceneSource::Kind::AssetPath;
  job.source.assetPath = "a/b.glb";
  job.assetRoot = "/assets";
  job.limits.maxTriangles = 1234;
  job.options.animation = lgh::SceneAnimation{2, 1.25F};
  job.options.materialVariant = "red";
  job.options.ignoreUnsupportedExtensions = true;
  job.options.textureCompression = lgh::TextureCompression::Bc;
  std::vector<std::uint8_t> bytes = bytesOf(lgh::worker::encodeJob(job));
  const lgh::worker::LoadJob decoded = lgh::worker::decodeJob(bytes);
  EXPECT_EQ(decoded.source.assetPath, "a/b.glb");
  EXPECT_EQ(decoded.limits.maxTriangles, 1234U);
  ASSERT_TRUE(decoded.options.animation.has_value());
  EXPECT_EQ(decoded.options.animation->index, 2);
  EXPECT_EQ(decoded.options.animation->time, 1.25F);
  EXPECT_EQ(decoded.options.materialVariant, "red");
  EXPECT_TRUE(decoded.options.ignoreUnsupportedExtensions);
  EXPECT_EQ(decoded.options.textureCompression, lgh::TextureCompression::Bc);
  // No animation stays none.
  job.options.animation.reset();
  EXPECT_FALSE(lgh::worker::decodeJob(bytesOf(lgh::worker::encodeJob(job))).options.animation);
  const auto expectRefused = [](const std::vector<std::uint8_t>& message, const char* what) {
    try {
      lgh::worker::decodeJob(message);
      ADD_FAILURE() << "decoded";
    } catch (const Error& error) {
      EXPECT_EQ(error.code(), ErrorCode::Internal);
      EXPECT_NE(std::string(error.message()).find(what), std::string::npos) << error.what();
    }
  };
  // The texture compression ends the job; an unknown one is refused.
  std::vector<std::uint8_t> unknownCompression = bytes;
  unknownCompression[bytes.size() - sizeof(lgh::TextureCompression)] = 7;
  expectRefused(unknownCompression, "texture compression");
  // The byte before it is the extension flag: a value other than 0 or 1 is refused, not loaded.
  bytes[bytes.size() - sizeof(lgh::TextureCompression) - 1] = 2;
  expectRefused(bytes, "neither 0 nor 1");
}

// What a misbehaving worker could send that the renderer would trust: each is refused by name.
TEST(SceneWire, OutOfRangeValuesAreRefused) {
  auto expectRefused = [](const Scene& scene, const char* what) {
    const Error error = refusal(scene);
    EXPECT_EQ(error.code(), ErrorCode::Internal) << what;
    EXPECT_NE(std::string(error.message()).find(what), std::string::npos) << error.what();
  };
  Scene scene = everyField();
  scene.meshes[0].primitives[0].indices.push_back(0);  // 7 indices: not whole triangles
  expectRefused(scene, "triangle list");
  scene = everyField();
  scene.meshes[0].primitives[0].topology = lgh::Topology::Lines;  // a line list among triangles
  expectRefused(scene, "triangle list");
  scene = everyField();
  scene.meshes[0].linesAndPoints[0].indices.push_back(1);  // 5 indices: not whole lines
  expectRefused(scene, "line or point list");
  scene = everyField();
  scene.meshes[0].linesAndPoints[1].topology = static_cast<lgh::Topology>(7);
  expectRefused(scene, "line or point list");
  scene = everyField();
  scene.meshes[0].linesAndPoints[1].indices[0] = 4;  // past the 4 vertices
  expectRefused(scene, "vertex index");
  scene = everyField();
  scene.meshes[0].linesAndPoints[0].material = 3;  // past the three materials
  expectRefused(scene, "a material");
  scene = everyField();
  scene.materials[0].model = static_cast<lgh::MaterialModel>(9);
  expectRefused(scene, "material model");
  scene = everyField();
  scene.materials[0].sheen.colorTexture.image = 2;  // a layer's texture past the two images
  expectRefused(scene, "texture's image");
  scene = everyField();
  scene.materials[0].transmission.texture.image = 5;
  expectRefused(scene, "texture's image");
  // Issue 22's fields.
  scene = everyField();
  scene.materials[2].classic.specularTexture.image = 2;
  expectRefused(scene, "texture's image");
  scene = everyField();
  scene.materials[0].surface.heightTexture.image = 2;
  expectRefused(scene, "texture's image");
  scene = everyField();
  scene.materials[0].lightMap.image = 9;
  expectRefused(scene, "texture's image");
  scene = everyField();
  scene.textures[1].image = 2;
  expectRefused(scene, "texture's image");
  scene = everyField();
  scene.materials[2].model = static_cast<lgh::MaterialModel>(6);  // one past Cook-Torrance
  expectRefused(scene, "material model");
  scene = everyField();
  scene.materials[2].classic.shading = static_cast<lgh::ShadingMode>(3);
  expectRefused(scene, "shading");
  scene = everyField();
  scene.materials[0].surface.technique = static_cast<lgh::SurfaceDetail>(6);
  expectRefused(scene, "surface detail technique");
  scene = everyField();
  scene.materials[0].surface.reliefLinearSteps = 1 << 20;
  expectRefused(scene, "step or tessellation count");
  scene = everyField();
  scene.materials[0].surface.tessellationMaxLevel = 0;
  expectRefused(scene, "step or tessellation count");
  // DDS payloads: uploaded as they are, so each must be exactly as long as its blocks.
  const auto withBlocks = [](auto change) {
    Scene changed = everyField();
    change(changed.compressedImages.at(1));
    return changed;
  };
  expectRefused(withBlocks([](lgh::BlockCompressedImage& b) { b.levels[1].pop_back(); }),
                "level's byte count");
  expectRefused(withBlocks([](lgh::BlockCompressedImage& b) { b.levels[0].resize(64); }),
                "level's byte count");
  expectRefused(withBlocks([](lgh::BlockCompressedImage& b) { b.width = 64; }),
                "compressed image's size");
  expectRefused(withBlocks([](lgh::BlockCompressedImage& b) { b.levels.clear(); }), "level count");
  expectRefused(
      withBlocks([](lgh::BlockCompressedImage& b) { b.format = static_cast<lgh::BlockFormat>(5); }),
      "block format");
  scene = everyField();
  scene.compressedImages.emplace(4, scene.compressedImages.at(1));  // no image 4
  expectRefused(scene, "compressed image's index");
}

}  // namespace
