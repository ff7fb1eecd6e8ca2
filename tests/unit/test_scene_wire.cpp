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
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using lgh::Error;
using lgh::ErrorCode;
using lgh::Scene;

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

template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectSameTexture(const lgh::TextureRef& a, const lgh::TextureRef& b, std::size_t slot) {
  SCOPED_TRACE("texture slot " + std::to_string(slot));
  EXPECT_EQ(a.image, b.image);
  EXPECT_EQ(a.texCoord, b.texCoord);
  EXPECT_EQ(a.sampler.magFilter, b.sampler.magFilter);
  EXPECT_EQ(a.sampler.minFilter, b.sampler.minFilter);
  EXPECT_EQ(a.sampler.wrapS, b.sampler.wrapS);
  EXPECT_EQ(a.sampler.wrapT, b.sampler.wrapT);
  EXPECT_EQ(a.sampler.borderColor, b.sampler.borderColor);
  EXPECT_EQ(a.sampler.anisotropy, b.sampler.anisotropy);
  EXPECT_EQ(a.transform.offset, b.transform.offset);
  EXPECT_EQ(a.transform.rotation, b.transform.rotation);
  EXPECT_EQ(a.transform.scale, b.transform.scale);
}

void expectSameMaterial(const lgh::Material& a, const lgh::Material& b) {
  SCOPED_TRACE("material " + a.name);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.baseColorFactor, b.baseColorFactor);
  EXPECT_EQ(a.metallicFactor, b.metallicFactor);
  EXPECT_EQ(a.roughnessFactor, b.roughnessFactor);
  EXPECT_EQ(a.emissiveFactor, b.emissiveFactor);
  EXPECT_EQ(a.normalScale, b.normalScale);
  EXPECT_EQ(a.occlusionStrength, b.occlusionStrength);
  EXPECT_EQ(a.alphaMode, b.alphaMode);
  EXPECT_EQ(a.alphaCutoff, b.alphaCutoff);
  EXPECT_EQ(a.doubleSided, b.doubleSided);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.clearcoat.factor, b.clearcoat.factor);
  EXPECT_EQ(a.clearcoat.roughness, b.clearcoat.roughness);
  EXPECT_EQ(a.clearcoat.normalScale, b.clearcoat.normalScale);
  EXPECT_EQ(a.sheen.colorFactor, b.sheen.colorFactor);
  EXPECT_EQ(a.sheen.roughnessFactor, b.sheen.roughnessFactor);
  EXPECT_EQ(a.specular.factor, b.specular.factor);
  EXPECT_EQ(a.specular.colorFactor, b.specular.colorFactor);
  EXPECT_EQ(a.specular.ior, b.specular.ior);
  EXPECT_EQ(a.transmission.factor, b.transmission.factor);
  EXPECT_EQ(a.transmission.thicknessFactor, b.transmission.thicknessFactor);
  EXPECT_EQ(a.transmission.attenuationColor, b.transmission.attenuationColor);
  EXPECT_EQ(a.transmission.attenuationDistance, b.transmission.attenuationDistance);
  EXPECT_EQ(a.classic.ambient, b.classic.ambient);
  EXPECT_EQ(a.classic.specular, b.classic.specular);
  EXPECT_EQ(a.classic.shininess, b.classic.shininess);
  EXPECT_EQ(a.classic.sigma, b.classic.sigma);
  EXPECT_EQ(a.classic.m, b.classic.m);
  EXPECT_EQ(a.classic.f0, b.classic.f0);
  EXPECT_EQ(a.classic.shading, b.classic.shading);
  expectSameTexture(a.classic.specularTexture, b.classic.specularTexture, 100);
  expectSameTexture(a.classic.shininessTexture, b.classic.shininessTexture, 101);
  EXPECT_EQ(a.surface.technique, b.surface.technique);
  EXPECT_EQ(a.surface.heightScale, b.surface.heightScale);
  EXPECT_EQ(a.surface.parallaxBias, b.surface.parallaxBias);
  EXPECT_EQ(a.surface.reliefLinearSteps, b.surface.reliefLinearSteps);
  EXPECT_EQ(a.surface.reliefBinarySteps, b.surface.reliefBinarySteps);
  EXPECT_EQ(a.surface.reliefSelfShadow, b.surface.reliefSelfShadow);
  EXPECT_EQ(a.surface.reliefSilhouettes, b.surface.reliefSilhouettes);
  EXPECT_EQ(a.surface.tessellationPixels, b.surface.tessellationPixels);
  EXPECT_EQ(a.surface.tessellationMaxLevel, b.surface.tessellationMaxLevel);
  expectSameTexture(a.surface.heightTexture, b.surface.heightTexture, 102);
  expectSameTexture(a.lightMap, b.lightMap, 103);
  EXPECT_EQ(a.lightMapStrength, b.lightMapStrength);
  EXPECT_EQ(a.bicubic, b.bicubic);
  EXPECT_EQ(a.hasLayers(), b.hasLayers());
  const auto slotsA = lgh::materialTextureSlots(a);
  const auto slotsB = lgh::materialTextureSlots(b);
  for (std::size_t i = 0; i < slotsA.size(); ++i) {
    expectSameTexture(*slotsA[i].texture, *slotsB[i].texture, i);
    EXPECT_EQ(slotsA[i].usage, slotsB[i].usage);
  }
}

void expectSamePrimitives(const std::vector<lgh::Primitive>& a,
                          const std::vector<lgh::Primitive>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t p = 0; p < a.size(); ++p) {
    SCOPED_TRACE("primitive " + std::to_string(p));
    EXPECT_TRUE(sameBytes(a[p].vertices, b[p].vertices));
    EXPECT_EQ(a[p].indices, b[p].indices);
    EXPECT_EQ(a[p].material, b[p].material);
    EXPECT_EQ(a[p].topology, b[p].topology);
    EXPECT_EQ(a[p].unlit, b[p].unlit);
    EXPECT_EQ(a[p].tangents, b[p].tangents);
  }
}

// Every field of Scene the renderer reads.
void expectSameScene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (std::size_t m = 0; m < a.meshes.size(); ++m) {
    SCOPED_TRACE("mesh " + std::to_string(m));
    EXPECT_EQ(a.meshes[m].name, b.meshes[m].name);
    expectSamePrimitives(a.meshes[m].primitives, b.meshes[m].primitives);
    expectSamePrimitives(a.meshes[m].linesAndPoints, b.meshes[m].linesAndPoints);
  }
  ASSERT_EQ(a.instances.size(), b.instances.size());
  for (std::size_t i = 0; i < a.instances.size(); ++i) {
    EXPECT_EQ(a.instances[i].mesh, b.instances[i].mesh);
    EXPECT_EQ(a.instances[i].world, b.instances[i].world);
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    expectSameMaterial(a.materials[i], b.materials[i]);
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (std::size_t i = 0; i < a.images.size(); ++i) {
    EXPECT_EQ(a.images[i].width, b.images[i].width);
    EXPECT_EQ(a.images[i].height, b.images[i].height);
    EXPECT_EQ(a.images[i].channels, b.images[i].channels);
    EXPECT_TRUE(sameBytes(a.images[i].pixels, b.images[i].pixels));
  }
  ASSERT_EQ(a.compressedImages.size(), b.compressedImages.size());
  for (const auto& [index, blocks] : a.compressedImages) {
    SCOPED_TRACE("compressed image " + std::to_string(index));
    ASSERT_EQ(b.compressedImages.count(index), 1U);
    const lgh::BlockCompressedImage& other = b.compressedImages.at(index);
    EXPECT_EQ(blocks.format, other.format);
    EXPECT_EQ(blocks.srgb, other.srgb);
    EXPECT_EQ(blocks.width, other.width);
    EXPECT_EQ(blocks.height, other.height);
    EXPECT_EQ(blocks.levels, other.levels);
  }
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (std::size_t i = 0; i < a.textures.size(); ++i) {
    expectSameTexture(a.textures[i], b.textures[i], 200 + i);
  }
  EXPECT_TRUE(sameBytes(a.lights, b.lights));
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (std::size_t i = 0; i < a.cameras.size(); ++i) {
    EXPECT_EQ(a.cameras[i].name, b.cameras[i].name);
    EXPECT_EQ(a.cameras[i].world, b.cameras[i].world);
    EXPECT_EQ(a.cameras[i].yfov, b.cameras[i].yfov);
  }
  EXPECT_EQ(a.bounds.min, b.bounds.min);
  EXPECT_EQ(a.bounds.max, b.bounds.max);
  EXPECT_EQ(a.warnings, b.warnings);
  EXPECT_EQ(a.triangleCount(), b.triangleCount());
  EXPECT_EQ(a.lineAndPointPrimitiveCount(), b.lineAndPointPrimitiveCount());
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
