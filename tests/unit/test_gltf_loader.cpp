// The glTF loader against real assets (Debian's assimp-testmodels), broken assets, hand-made
// assets for the features those do not cover, and mutated GLBs.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <webp/decode.h>
#include <webp/encode.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "lgh/error.hpp"
#include "lgh/image.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using lgh::Error;
using lgh::ErrorCode;
using lgh::Scene;
using json = nlohmann::json;

fs::path models() { return lgh::test::assimpGltfDir(); }

bool isGltfFile(const fs::path& path) {
  return path.extension() == ".gltf" || path.extension() == ".glb";
}

// Every .gltf/.glb under `dir`, sorted (for stable test output).
std::vector<fs::path> gltfFilesUnder(const fs::path& dir) {
  std::vector<fs::path> files;
  if (!fs::is_directory(dir)) return files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file() && isGltfFile(entry.path())) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Loads a file with its own folder as the asset root.
Scene loadFile(const fs::path& path, const lgh::SceneLoadLimits& limits = {}) {
  return lgh::loadGltfFile(path.parent_path(), path.filename().string(), limits);
}

// The lgh::Error loading `path` throws; a failure when it loads or throws something else.
Error loadError(const fs::path& path, const lgh::SceneLoadLimits& limits = {}) {
  try {
    loadFile(path, limits);
  } catch (const Error& error) {
    return error;
  } catch (const std::exception& error) {
    ADD_FAILURE() << path << " threw a non-lgh exception: " << error.what();
    return Error(ErrorCode::Internal, error.what());
  }
  ADD_FAILURE() << path << " loaded";
  return Error(ErrorCode::Internal, "loaded");
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

bool anyWarningContains(const Scene& scene, const std::string& part) {
  return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                     [&](const std::string& warning) { return contains(warning, part); });
}

// What every successfully loaded scene must satisfy.
void expectSane(const Scene& scene, const std::string& what) {
  EXPECT_GT(scene.triangleCount(), 0U) << what;
  ASSERT_FALSE(scene.bounds.empty()) << what;
  EXPECT_TRUE(finite(scene.bounds.min) && finite(scene.bounds.max)) << what;
  for (const lgh::MeshInstance& instance : scene.instances) {
    ASSERT_GE(instance.mesh, 0) << what;
    ASSERT_LT(static_cast<std::size_t>(instance.mesh), scene.meshes.size()) << what;
  }
  for (const lgh::Mesh& mesh : scene.meshes) {
    for (const lgh::Primitive& primitive : mesh.primitives) {
      ASSERT_EQ(primitive.indices.size() % 3, 0U) << what;
      for (std::uint32_t index : primitive.indices) {
        ASSERT_LT(index, primitive.vertices.size()) << what;
      }
      if (primitive.material >= 0) {
        ASSERT_LT(static_cast<std::size_t>(primitive.material), scene.materials.size()) << what;
      }
      for (const lgh::Vertex& v : primitive.vertices) {
        ASSERT_NEAR(glm::length(v.normal), 1.0F, 1e-3F) << what << " " << mesh.name;
        ASSERT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0F, 1e-3F) << what << " " << mesh.name;
        ASSERT_EQ(std::abs(v.tangent.w), 1.0F) << what;
      }
    }
  }
  for (const lgh::Material& material : scene.materials) {
    for (const lgh::TextureRef* ref :
         {&material.baseColorTexture, &material.normalTexture, &material.metallicRoughnessTexture,
          &material.occlusionTexture, &material.emissiveTexture}) {
      if (!ref->valid()) continue;
      ASSERT_LT(static_cast<std::size_t>(ref->image), scene.images.size()) << what;
      const lgh::Image8& image = scene.images[static_cast<std::size_t>(ref->image)];
      EXPECT_EQ(image.channels, 4) << what;
      EXPECT_EQ(image.pixels.size(), static_cast<std::size_t>(image.width) * image.height * 4);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Real, valid assets.

// glTF-Sample-Models in either layout: upstream's <Model>/glTF{,-Binary,-Embedded,...}/ or
// Debian's flattened <Model>-glTF/.
TEST(GltfLoader, SampleModelsLoad) {
  const auto files = gltfFilesUnder(models() / "glTF-Sample-Models");
  ASSERT_FALSE(files.empty()) << "assimp-testmodels not installed?";
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    try {
      expectSane(loadFile(file), file.string());
    } catch (const Error& error) {
      ADD_FAILURE() << file << ": " << error.what();
    }
  }
}

// The other valid assets at the top of the collection, each directory as a whole.
TEST(GltfLoader, OtherValidModelsLoad) {
  const std::vector<std::string> directories = {"2CylinderEngine-glTF-Binary",
                                                "BoxTexcoords-glTF",
                                                "BoxTextured-glTF",
                                                "BoxTextured-glTF-Binary",
                                                "BoxTextured-glTF-Embedded",
                                                "BoxTextured-glTF-pbrSpecularGlossiness",
                                                "ClearCoat-glTF",
                                                "cameras",
                                                "simple_skin",
                                                "textureTransform",
                                                "draco"};
  std::size_t loaded = 0;
  for (const std::string& directory : directories) {
    for (const fs::path& file : gltfFilesUnder(models() / directory)) {
      SCOPED_TRACE(file.string());
      try {
        expectSane(loadFile(file), file.string());
        ++loaded;
      } catch (const Error& error) {
        ADD_FAILURE() << file << ": " << error.what();
      }
    }
  }
  EXPECT_GE(loaded, directories.size());
}

TEST(GltfLoader, TexturedBoxHasDecodedBaseColorTexture) {
  for (const char* file :
       {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
        "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    SCOPED_TRACE(file);
    const Scene scene = loadFile(models() / file);
    EXPECT_EQ(scene.triangleCount(), 12U);
    ASSERT_EQ(scene.materials.size(), 1U);
    const lgh::TextureRef& base = scene.materials[0].baseColorTexture;
    ASSERT_TRUE(base.valid());
    EXPECT_EQ(base.texCoord, 0);
    ASSERT_EQ(scene.images.size(), 1U);
    EXPECT_GT(scene.images[0].width, 0);
    EXPECT_EQ(scene.images[0].channels, 4);
    EXPECT_FLOAT_EQ(scene.materials[0].metallicFactor, 0.0F);
    // The box is 1 unit, centred at the origin.
    EXPECT_NEAR(scene.bounds.size().x, 1.0F, 1e-4F);
    EXPECT_NEAR(scene.bounds.center().y, 0.0F, 1e-4F);
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  }
}

TEST(GltfLoader, UnsupportedOptionalExtensionsWarn) {
  const Scene legacy =
      loadFile(models() / "BoxTextured-glTF-pbrSpecularGlossiness" / "BoxTextured.gltf");
  EXPECT_TRUE(anyWarningContains(legacy, "KHR_materials_pbrSpecularGlossiness"));
}

TEST(GltfLoader, ClearcoatMaterialsAreRead) {
  const Scene scene = loadFile(models() / "ClearCoat-glTF" / "ClearCoatTest.gltf");
  EXPECT_FALSE(anyWarningContains(scene, "KHR_materials_clearcoat"));
  std::size_t coated = 0;
  std::size_t textured = 0;
  for (const lgh::Material& material : scene.materials) {
    if (material.clearcoat.factor > 0.0F) ++coated;
    if (material.clearcoat.texture.valid() || material.clearcoat.normalTexture.valid()) ++textured;
    EXPECT_LE(material.clearcoat.factor, 1.0F);
  }
  EXPECT_GE(coated, 5U);
  EXPECT_GE(textured, 1U);
}

TEST(GltfLoader, TextureTransformsAreRead) {
  const Scene scene = loadFile(models() / "textureTransform" / "TextureTransformTest.gltf");
  EXPECT_FALSE(anyWarningContains(scene, "KHR_texture_transform"));
  bool rotated = false;
  bool offset = false;
  bool scaled = false;
  for (const lgh::Material& material : scene.materials) {
    const lgh::UvTransform& t = material.baseColorTexture.transform;
    rotated = rotated || std::abs(t.rotation - 0.392699F) < 1e-5F;
    offset = offset || t.offset != glm::vec2(0.0F);
    scaled = scaled || t.scale == glm::vec2(1.5F);
  }
  EXPECT_TRUE(rotated);
  EXPECT_TRUE(offset);
  EXPECT_TRUE(scaled);
}

TEST(GltfLoader, Cameras) {
  const Scene scene = loadFile(models() / "cameras" / "Cameras.gltf");
  ASSERT_EQ(scene.cameras.size(), 2U);
  const lgh::SceneCamera& perspective = scene.cameras[0];
  EXPECT_TRUE(perspective.perspective);
  EXPECT_FLOAT_EQ(perspective.yfov, 0.7F);
  EXPECT_FLOAT_EQ(perspective.aspectRatio, 1.0F);
  EXPECT_FLOAT_EQ(perspective.znear, 0.01F);
  EXPECT_FLOAT_EQ(perspective.zfar, 100.0F);
  EXPECT_EQ(glm::vec3(perspective.world[3]), glm::vec3(0.5F, 0.5F, 3.0F));
  const lgh::SceneCamera& orthographic = scene.cameras[1];
  EXPECT_FALSE(orthographic.perspective);
  EXPECT_FLOAT_EQ(orthographic.xmag, 1.0F);
  EXPECT_FLOAT_EQ(orthographic.ymag, 1.0F);
}

// Only TEXCOORD_1 while the material samples TEXCOORD_0 (assimp issue 3269): the Khronos
// validator's MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY, refused naming the attributes.
TEST(GltfLoader, MissingTexcoordSetIsAnError) {
  const Error error = loadError(models() / "issue_3269" / "texcoord_crash.gltf");
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(error.message(),
                       "/meshes/0/primitives/0/attributes has TEXCOORD_1 without TEXCOORD_0"))
      << error.what();
}

// ---------------------------------------------------------------------------------------------
// glTF-Asset-Generator: every suite present, every model loads. Models that hold only points or
// lines (listed here) load as lines and points.
const std::set<std::string> kPointsAndLinesOnly = {
    "Mesh_PrimitiveMode_00", "Mesh_PrimitiveMode_01", "Mesh_PrimitiveMode_02",
    "Mesh_PrimitiveMode_03", "Mesh_PrimitiveMode_07", "Mesh_PrimitiveMode_08",
    "Mesh_PrimitiveMode_09", "Mesh_PrimitiveMode_10"};

TEST(GltfLoader, AssetGeneratorSuites) {
  const auto files = gltfFilesUnder(models() / "glTF-Asset-Generator");
  ASSERT_FALSE(files.empty());
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    const std::string stem = file.stem().string();
    if (kPointsAndLinesOnly.count(stem) != 0) {
      const Scene scene = loadFile(file);
      EXPECT_EQ(scene.triangleCount(), 0U);
      EXPECT_GE(scene.lineAndPointPrimitiveCount(), 1U);
      EXPECT_FALSE(scene.bounds.empty());
      continue;
    }
    try {
      expectSane(loadFile(file), file.string());
    } catch (const std::exception& error) {
      ADD_FAILURE() << file << ": " << error.what();
    }
  }
}

// Strips and fans (indexed and not, every index type) become lists with the spec's winding: each
// model is a quad facing +Z, two triangles.
TEST(GltfLoader, PrimitiveModesBecomeCounterClockwiseLists) {
  const fs::path suite = models() / "glTF-Asset-Generator" / "Mesh_PrimitiveMode";
  for (const char* stem : {"04", "05", "06", "11", "12", "13", "14", "15"}) {
    const fs::path file = suite / ("Mesh_PrimitiveMode_" + std::string(stem) + ".gltf");
    SCOPED_TRACE(file.string());
    const Scene scene = loadFile(file);
    ASSERT_EQ(scene.triangleCount(), 2U);
    const lgh::Primitive& primitive = scene.meshes.at(0).primitives.at(0);
    for (std::size_t i = 0; i < primitive.indices.size(); i += 3) {
      const glm::vec3 a = primitive.vertices[primitive.indices[i]].position;
      const glm::vec3 b = primitive.vertices[primitive.indices[i + 1]].position;
      const glm::vec3 c = primitive.vertices[primitive.indices[i + 2]].position;
      const glm::vec3 world = glm::mat3(scene.instances.at(0).world) * glm::cross(b - a, c - a);
      EXPECT_GT(world.z, 0.0F);
      // No NORMAL in these: flat normals, along the face.
      EXPECT_GT(glm::dot(primitive.vertices[primitive.indices[i]].normal, glm::cross(b - a, c - a)),
                0.0F);
    }
  }
}

// Points, lines, line loops and line strips (Mesh_PrimitiveMode_00..03) become point and line
// lists: a loop closes, a strip does not; without NORMAL they are unlit.
TEST(GltfLoader, PointsAndLinesBecomeLists) {
  const fs::path suite = models() / "glTF-Asset-Generator" / "Mesh_PrimitiveMode";
  const Scene points = loadFile(suite / "Mesh_PrimitiveMode_00.gltf");
  const lgh::Primitive& p = points.meshes.at(0).linesAndPoints.at(0);
  EXPECT_EQ(p.topology, lgh::Topology::Points);
  EXPECT_EQ(p.indices.size(), p.vertices.size());
  EXPECT_TRUE(p.unlit);
  const Scene lines = loadFile(suite / "Mesh_PrimitiveMode_01.gltf");
  const lgh::Primitive& l = lines.meshes.at(0).linesAndPoints.at(0);
  EXPECT_EQ(l.topology, lgh::Topology::Lines);
  EXPECT_EQ(l.indices.size() % 2, 0U);
  const Scene loop = loadFile(suite / "Mesh_PrimitiveMode_02.gltf");
  const lgh::Primitive& lp = loop.meshes.at(0).linesAndPoints.at(0);
  const Scene strip = loadFile(suite / "Mesh_PrimitiveMode_03.gltf");
  const lgh::Primitive& st = strip.meshes.at(0).linesAndPoints.at(0);
  // n vertices: a loop has n segments, a strip n - 1.
  EXPECT_EQ(lp.indices.size(), 2 * lp.vertices.size());
  EXPECT_EQ(st.indices.size(), 2 * (st.vertices.size() - 1));
  EXPECT_EQ(lp.indices.back(), lp.indices.front());
}

// ---------------------------------------------------------------------------------------------
// Broken assets: per directory, the expected outcome.

// wrongTypes/: members of the wrong JSON type. tinygltf would silently drop them; the schema
// pre-check names the JSON pointer instead.
TEST(GltfLoaderBroken, WrongTypesNameTheMember) {
  const std::map<std::string, std::string> expected = {
      {"badArray.gltf", "/meshes/0/primitives must be an array"},
      {"badExtension.gltf", "/extensions/KHR_texture_transform must be an object"},
      {"badNumber.gltf", "/materials/0/normalTexture/scale must be a number"},
      {"badObject.gltf", "/materials/0/pbrMetallicRoughness must be an object"},
      {"badString.gltf", "/name must be a string"},
      {"badUint.gltf", "/index must be a non-negative integer"}};
  const auto files = gltfFilesUnder(models() / "wrongTypes");
  ASSERT_EQ(files.size(), expected.size());
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    const Error error = loadError(file);
    EXPECT_EQ(error.code(), ErrorCode::Invalid);
    EXPECT_EQ(error.field(), file.filename().string());
    ASSERT_EQ(expected.count(file.filename().string()), 1U);
    EXPECT_TRUE(contains(error.message(), expected.at(file.filename().string()))) << error.what();
  }
}

TEST(GltfLoaderBroken, SchemaFailuresNameTheMember) {
  const auto files = gltfFilesUnder(models() / "SchemaFailures");
  ASSERT_FALSE(files.empty());
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    const Error error = loadError(file);
    EXPECT_EQ(error.code(), ErrorCode::Invalid);
    EXPECT_TRUE(contains(error.message(), "/scene must be a non-negative integer")) << error.what();
  }
}

TEST(GltfLoaderBroken, IndexOutOfRangeIsAnError) {
  const auto files = gltfFilesUnder(models() / "IndexOutOfRange");
  ASSERT_EQ(files.size(), 2U);
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    const Error error = loadError(file);
    EXPECT_EQ(error.code(), ErrorCode::Invalid);
    EXPECT_TRUE(contains(error.message(), "out of range for 24 vertices")) << error.what();
    EXPECT_TRUE(contains(error.message(), "/meshes/0/primitives/0/indices")) << error.what();
  }
}

TEST(GltfLoaderBroken, MissingBinIsNotFoundNamingTheFile) {
  const auto files = gltfFilesUnder(models() / "MissingBin");
  ASSERT_FALSE(files.empty());
  for (const fs::path& file : files) {
    const Error error = loadError(file);
    EXPECT_EQ(error.code(), ErrorCode::NotFound);
    EXPECT_TRUE(contains(error.message(), "BoxTextured0.bin")) << error.what();
  }
}

TEST(GltfLoaderBroken, InfinitePositionsAreAnError) {
  const auto files = gltfFilesUnder(models() / "BoxWithInfinites-glTF-Binary");
  ASSERT_FALSE(files.empty());
  for (const fs::path& file : files) {
    const Error error = loadError(file);
    EXPECT_EQ(error.code(), ErrorCode::Invalid);
    EXPECT_TRUE(contains(error.message(), "non-finite value")) << error.what();
    EXPECT_TRUE(contains(error.message(), "/meshes/0/primitives/0/attributes/POSITION"))
        << error.what();
  }
}

TEST(GltfLoaderBroken, RecursiveNodesAreAnError) {
  const auto files = gltfFilesUnder(models() / "RecursiveNodes");
  ASSERT_FALSE(files.empty());
  for (const fs::path& file : files) {
    const Error error = loadError(file);
    EXPECT_EQ(error.code(), ErrorCode::Invalid);
    // Nodes 0 and 1 are each other's child: the scene's root has a parent (the validator's
    // SCENE_NON_ROOT_NODE, at the same pointer).
    EXPECT_TRUE(contains(error.message(), "/scenes/0/nodes/0 names node 0, a child of /nodes/1"))
        << error.what();
  }
}

// BoxBadNormals: zero/NaN normals are repaired (smooth normals) with a warning.
TEST(GltfLoaderBroken, BadNormalsAreRepaired) {
  const auto files = gltfFilesUnder(models() / "BoxBadNormals-glTF-Binary");
  ASSERT_FALSE(files.empty());
  for (const fs::path& file : files) {
    const Scene scene = loadFile(file);
    expectSane(scene, file.string());
    EXPECT_TRUE(anyWarningContains(scene, "normals replaced")) << file;
  }
}

// IncorrectVertexArrays: vertex/index counts that are not multiples of three, line primitives,
// and a bufferView longer than its buffer.
TEST(GltfLoaderBroken, IncorrectVertexArraysAreAnError) {
  // Its bufferView 2 reaches past the end of its buffer (the validator's BUFFER_VIEW_TOO_LONG).
  const Error error = loadError(models() / "IncorrectVertexArrays" / "Cube.gltf");
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(error.message(),
                       "/bufferViews/2 (byteOffset 504, byteLength 432) reaches "
                       "past the end of /buffers/0"))
      << error.what();
}

// TestNoRootNode: a default scene that does not exist is an error (the validator's
// UNRESOLVED_REFERENCE); a scene without nodes draws nothing: an empty scene and a warning.
TEST(GltfLoaderBroken, NoRootNodeMeansAnErrorOrAnEmptyScene) {
  const Error noScene = loadError(models() / "TestNoRootNode" / "NoScene.gltf");
  EXPECT_EQ(noScene.code(), ErrorCode::Invalid);
  EXPECT_EQ(noScene.message(),
            "invalid glTF: /scene names scene 0, which does not exist (the "
            "asset has 0)");
  const Scene noNodes = loadFile(models() / "TestNoRootNode" / "SceneWithoutNodes.gltf");
  EXPECT_EQ(noNodes.triangleCount(), 0U);
  EXPECT_TRUE(anyWarningContains(noNodes, "no geometry"));
}

TEST(GltfLoaderBroken, RequiredUnsupportedExtensionsAreNamed) {
  const fs::path file = models() / "BoxTextured-glTF-techniqueWebGL" / "BoxTextured.gltf";
  const Error technique = loadError(file);
  EXPECT_EQ(technique.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(technique.message(), "KHR_technique_webgl")) << technique.what();
  EXPECT_TRUE(contains(technique.message(), "ignore_unsupported_extensions")) << technique.what();
  // settings.ignore_unsupported_extensions: rendered without it, with a warning.
  lgh::SceneLoadOptions options;
  options.ignoreUnsupportedExtensions = true;
  const Scene scene =
      lgh::loadGltfFile(models(), fs::relative(file, models()).string(), {}, options);
  EXPECT_EQ(scene.triangleCount(), 12U);
  EXPECT_TRUE(anyWarningContains(scene, "KHR_technique_webgl"));
}

// KHR_draco_mesh_compression: the Draco copy of 2CylinderEngine decodes to the triangle counts its
// index accessors declare (65311 over its meshes; Draco's encoder dropped the degenerate
// triangles of the plain GLB), placed as the plain GLB's.
TEST(GltfLoader, DracoDecodesToTheDeclaredGeometry) {
  const Scene draco = loadFile(models() / "draco" / "2CylinderEngine.gltf");
  const Scene plain = loadFile(models() / "2CylinderEngine-glTF-Binary" / "2CylinderEngine.glb");
  std::size_t meshTriangles = 0;
  for (const lgh::Mesh& mesh : draco.meshes) {
    for (const lgh::Primitive& primitive : mesh.primitives)
      meshTriangles += primitive.indices.size() / 3;
  }
  EXPECT_EQ(meshTriangles, 65311U);
  EXPECT_EQ(draco.instances.size(), plain.instances.size());
  // Draco quantizes positions: the bounds agree to a small fraction of their size.
  const float tolerance = 1e-3F * glm::length(plain.bounds.size());
  EXPECT_NEAR(glm::distance(draco.bounds.min, plain.bounds.min), 0.0F, tolerance);
  EXPECT_NEAR(glm::distance(draco.bounds.max, plain.bounds.max), 0.0F, tolerance);
}

// ---------------------------------------------------------------------------------------------
// Limits.

TEST(GltfLoaderLimits, TriangleLimit) {
  lgh::SceneLoadLimits limits;
  limits.maxTriangles = 11;  // the box has 12
  EXPECT_EQ(loadError(models() / "BoxTextured-glTF" / "BoxTextured.gltf", limits).code(),
            ErrorCode::TooLarge);
  limits.maxTriangles = 12;
  EXPECT_EQ(loadFile(models() / "BoxTextured-glTF" / "BoxTextured.gltf", limits).triangleCount(),
            12U);
}

TEST(GltfLoaderLimits, FileSizeLimit) {
  lgh::SceneLoadLimits limits;
  limits.maxFileBytes = 1000;
  EXPECT_EQ(loadError(models() / "BoxTextured-glTF-Binary" / "BoxTextured.glb", limits).code(),
            ErrorCode::TooLarge);
  // Side files count too: the .gltf is under 4 kB, its texture is not.
  limits.maxFileBytes = 2000;
  const Error error = loadError(models() / "BoxTexcoords-glTF" / "boxTexcoords.gltf", limits);
  EXPECT_EQ(error.code(), ErrorCode::TooLarge) << error.what();
}

TEST(GltfLoaderLimits, TextureSizeLimit) {
  lgh::SceneLoadLimits limits;
  limits.maxTextureSize = 16;
  const Error error = loadError(models() / "BoxTextured-glTF" / "BoxTextured.gltf", limits);
  EXPECT_EQ(error.code(), ErrorCode::TooLarge);
  EXPECT_TRUE(contains(error.message(), "CesiumLogoFlat.png")) << error.what();
}

// ---------------------------------------------------------------------------------------------
// Hand-made assets, held in memory.

// Builds a glTF with one binary buffer ("model.bin") and its JSON document.
class GltfBuilder {
 public:
  GltfBuilder() {
    doc_ = {
        {"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", json::array()}}}}};
  }

  json& doc() { return doc_; }

  int addView(const void* data, std::size_t size) {
    while (bin_.size() % 4 != 0) bin_.push_back(0);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    doc_["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", size}});
    bin_.insert(bin_.end(), bytes, bytes + size);
    return static_cast<int>(doc_["bufferViews"].size()) - 1;
  }

  int addAccessor(json accessor) {
    doc_["accessors"].push_back(std::move(accessor));
    return static_cast<int>(doc_["accessors"].size()) - 1;
  }

  int addFloats(const std::vector<float>& values, const char* type, std::size_t count) {
    const int view = addView(values.data(), values.size() * sizeof(float));
    return addAccessor(
        {{"bufferView", view}, {"componentType", 5126}, {"count", count}, {"type", type}});
  }

  // A one-primitive mesh from float positions (VEC3, with the min/max glTF requires); returns
  // the mesh index.
  int addMesh(const std::vector<float>& positions, json attributes = json::object(), int mode = 4) {
    attributes["POSITION"] = addFloats(positions, "VEC3", positions.size() / 3);
    json low = json::array();
    json high = json::array();
    for (std::size_t c = 0; c < 3; ++c) {
      float lowest = positions[c];
      float highest = positions[c];
      for (std::size_t i = c; i < positions.size(); i += 3) {
        lowest = std::min(lowest, positions[i]);
        highest = std::max(highest, positions[i]);
      }
      low.push_back(lowest);
      high.push_back(highest);
    }
    doc_["accessors"][attributes["POSITION"].get<int>()]["min"] = low;
    doc_["accessors"][attributes["POSITION"].get<int>()]["max"] = high;
    doc_["meshes"].push_back({{"primitives", {{{"attributes", attributes}, {"mode", mode}}}}});
    return static_cast<int>(doc_["meshes"].size()) - 1;
  }

  int addNode(json node, bool root = true) {
    doc_["nodes"].push_back(std::move(node));
    const int index = static_cast<int>(doc_["nodes"].size()) - 1;
    if (root) doc_["scenes"][0]["nodes"].push_back(index);
    return index;
  }

  std::map<std::string, std::vector<std::uint8_t>> files() {
    json doc = doc_;
    doc["buffers"] = {
        {{"uri", "model.bin"}, {"byteLength", std::max<std::size_t>(bin_.size(), 4)}}};
    std::vector<std::uint8_t> bin = bin_;
    bin.resize(std::max<std::size_t>(bin.size(), 4), 0);
    const std::string text = doc.dump();
    return {{"model.gltf", {text.begin(), text.end()}}, {"model.bin", bin}};
  }

  Scene load() { return lgh::loadGltfFromMemory("model.gltf", files()); }

  Error loadError() {
    try {
      load();
    } catch (const Error& error) {
      return error;
    }
    ADD_FAILURE() << "loaded";
    return Error(ErrorCode::Internal, "loaded");
  }

 private:
  json doc_;
  std::vector<std::uint8_t> bin_;
};

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

TEST(GltfLoaderFeatures, NodeHierarchyComposesTransforms) {
  GltfBuilder gltf;
  const int mesh = gltf.addMesh(kTriangle);
  const int child = gltf.addNode({{"mesh", mesh}, {"translation", {0, 0, 5}}}, false);
  // Parent: translate (1,0,0), rotate 90 degrees about Z, scale 2.
  const float s = std::sqrt(0.5F);
  gltf.addNode({{"children", {child}},
                {"translation", {1, 0, 0}},
                {"rotation", {0, 0, s, s}},
                {"scale", {2, 2, 2}}});
  // And a matrix node: translate (0, 10, 0), column-major.
  gltf.addNode({{"mesh", mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 10, 0, 1}}});
  const Scene scene = gltf.load();
  ASSERT_EQ(scene.instances.size(), 2U);
  ASSERT_EQ(scene.meshes.size(), 1U);  // one mesh, instanced twice
  EXPECT_EQ(scene.triangleCount(), 2U);
  const glm::mat4& world = scene.instances[0].world;
  // Local (1,0,0) of the child -> (1,0,5) -> scaled (2,0,10) -> rotated (0,2,10) -> (1,2,10).
  const glm::vec3 p(world * glm::vec4(1, 0, 0, 1));
  EXPECT_NEAR(p.x, 1.0F, 1e-5F);
  EXPECT_NEAR(p.y, 2.0F, 1e-5F);
  EXPECT_NEAR(p.z, 10.0F, 1e-5F);
  EXPECT_EQ(glm::vec3(scene.instances[1].world[3]), glm::vec3(0, 10, 0));
  EXPECT_NEAR(scene.bounds.max.z, 10.0F, 1e-5F);
}

TEST(GltfLoaderFeatures, WithoutScenesAllParentlessNodesAreRoots) {
  GltfBuilder gltf;
  const int mesh = gltf.addMesh(kTriangle);
  const int child = gltf.addNode({{"mesh", mesh}}, false);
  gltf.addNode({{"children", {child}}}, false);
  gltf.addNode({{"mesh", mesh}}, false);
  gltf.doc().erase("scenes");
  gltf.doc().erase("scene");
  const Scene scene = gltf.load();
  EXPECT_EQ(scene.instances.size(), 2U);  // the child once (via its parent), the loose node once
}

TEST(GltfLoaderFeatures, DeepHierarchyIsAnError) {
  GltfBuilder gltf;
  const int mesh = gltf.addMesh(kTriangle);
  int previous = gltf.addNode({{"mesh", mesh}}, false);
  for (int i = 0; i < 70; ++i) previous = gltf.addNode({{"children", {previous}}}, false);
  gltf.doc()["scenes"][0]["nodes"] = {previous};
  const Error error = gltf.loadError();
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(error.message(), "deeper than 64")) << error.what();
}

TEST(GltfLoaderFeatures, SharedSubtreesCannotExplode) {
  GltfBuilder gltf;
  const int mesh = gltf.addMesh(kTriangle);
  int previous = gltf.addNode({{"mesh", mesh}}, false);
  // Each level references the one below twice: 2^40 leaf instances if expanded. glTF's
  // hierarchy is a set of trees, so the second reference is already an error.
  for (int i = 0; i < 40; ++i) previous = gltf.addNode({{"children", {previous, previous}}}, false);
  gltf.doc()["scenes"][0]["nodes"] = {previous};
  const Error twice = gltf.loadError();
  EXPECT_EQ(twice.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(twice.message(), "/nodes/1/children/1 names node 0 twice")) << twice.what();
  // Two parents each: still not a tree.
  GltfBuilder shared;
  const int leaf = shared.addNode({{"mesh", shared.addMesh(kTriangle)}}, false);
  const int left = shared.addNode({{"children", {leaf}}}, false);
  const int right = shared.addNode({{"children", {leaf}}}, false);
  shared.doc()["scenes"][0]["nodes"] = {left, right};
  const Error parents = shared.loadError();
  EXPECT_EQ(parents.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(parents.message(), "at most one parent")) << parents.what();
}

TEST(GltfLoaderFeatures, PunctualLightsArePlacedByTheirNodes) {
  GltfBuilder gltf;
  gltf.addNode({{"mesh", gltf.addMesh(kTriangle)}});
  gltf.doc()["extensionsUsed"] = {"KHR_lights_punctual"};
  gltf.doc()["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", {1, 0.5, 0.25}}, {"intensity", 5}, {"range", 10}},
      {{"type", "spot"},
       {"intensity", 2},
       {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
      {{"type", "directional"}, {"intensity", 3}}};
  auto lightNode = [](int light) { return json{{"KHR_lights_punctual", {{"light", light}}}}; };
  const float s = std::sqrt(0.5F);
  gltf.addNode({{"translation", {1, 2, 3}}, {"extensions", lightNode(0)}});
  gltf.addNode(
      {{"translation", {0, 4, 0}}, {"rotation", {-s, 0, 0, s}}, {"extensions", lightNode(1)}});
  gltf.addNode({{"extensions", lightNode(2)}});
  const Scene scene = gltf.load();
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  ASSERT_EQ(scene.lights.size(), 3U);
  const lgh::LightDesc& point = scene.lights[0];
  EXPECT_EQ(point.type, lgh::LightType::Point);
  EXPECT_EQ(point.position, (std::array<float, 3>{1, 2, 3}));
  EXPECT_EQ(point.color, (std::array<float, 3>{1, 0.5F, 0.25F}));
  EXPECT_EQ(point.intensity, 5.0F);
  EXPECT_EQ(point.range, 10.0F);
  EXPECT_EQ(point.attenuation, (std::array<float, 3>{0, 0, 1}));
  const lgh::LightDesc& spot = scene.lights[1];
  EXPECT_EQ(spot.type, lgh::LightType::Spot);
  EXPECT_NEAR(spot.direction[1], -1.0F, 1e-5F);  // -Z turned -90 degrees about X: down
  EXPECT_NEAR(spot.innerConeAngle, 0.2F, 1e-6F);
  EXPECT_NEAR(spot.outerConeAngle, 0.5F, 1e-6F);
  const lgh::LightDesc& sun = scene.lights[2];
  EXPECT_EQ(sun.type, lgh::LightType::Directional);
  EXPECT_EQ(sun.direction, (std::array<float, 3>{0, 0, -1}));
}

TEST(GltfLoaderFeatures, MaterialFactorsSamplersAndEmissiveStrength) {
  GltfBuilder gltf;
  json attributes;
  attributes["TEXCOORD_0"] = gltf.addFloats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
  attributes["TEXCOORD_1"] = gltf.addFloats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
  const int mesh = gltf.addMesh(kTriangle, attributes);
  gltf.doc()["meshes"][mesh]["primitives"][0]["material"] = 0;
  gltf.addNode({{"mesh", mesh}});
  // A 1x1 PNG, encoded by our own image I/O.
  lgh::Image8 pixel;
  pixel.width = pixel.height = 1;
  pixel.pixels = {255, 0, 0, 255};
  const std::vector<std::uint8_t> png = lgh::image_io::encodePng(pixel);
  const int view = gltf.addView(png.data(), png.size());
  gltf.doc()["images"] = {{{"bufferView", view}, {"mimeType", "image/png"}}};
  gltf.doc()["samplers"] = {
      {{"magFilter", 9728}, {"minFilter", 9984}, {"wrapS", 33071}, {"wrapT", 33648}}};
  gltf.doc()["textures"] = {{{"source", 0}, {"sampler", 0}}};
  gltf.doc()["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  gltf.doc()["materials"] = {
      {{"name", "m"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.25, 1, 0.5}},
         {"metallicFactor", 0.1},
         {"roughnessFactor", 0.7},
         {"baseColorTexture", {{"index", 0}}}}},
       {"normalTexture", {{"index", 0}, {"scale", 0.5}, {"texCoord", 1}}},
       {"occlusionTexture", {{"index", 0}, {"strength", 0.25}}},
       {"emissiveTexture", {{"index", 0}}},
       {"emissiveFactor", {1, 0.5, 0}},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}},
       {"alphaMode", "MASK"},
       {"alphaCutoff", 0.3},
       {"doubleSided", true}}};
  const Scene scene = gltf.load();
  ASSERT_EQ(scene.materials.size(), 1U);
  const lgh::Material& m = scene.materials[0];
  EXPECT_EQ(m.name, "m");
  EXPECT_EQ(m.baseColorFactor, glm::vec4(0.5F, 0.25F, 1.0F, 0.5F));
  EXPECT_FLOAT_EQ(m.metallicFactor, 0.1F);
  EXPECT_FLOAT_EQ(m.roughnessFactor, 0.7F);
  EXPECT_EQ(m.emissiveFactor, glm::vec3(4.0F, 2.0F, 0.0F));
  EXPECT_FLOAT_EQ(m.normalScale, 0.5F);
  EXPECT_FLOAT_EQ(m.occlusionStrength, 0.25F);
  EXPECT_EQ(m.alphaMode, lgh::AlphaMode::Mask);
  EXPECT_FLOAT_EQ(m.alphaCutoff, 0.3F);
  EXPECT_TRUE(m.doubleSided);
  EXPECT_EQ(m.normalTexture.texCoord, 1);
  ASSERT_TRUE(m.baseColorTexture.valid());
  EXPECT_EQ(m.baseColorTexture.sampler.magFilter, 9728);
  EXPECT_EQ(m.baseColorTexture.sampler.minFilter, 9984);
  EXPECT_EQ(m.baseColorTexture.sampler.wrapS, 33071);
  EXPECT_EQ(m.baseColorTexture.sampler.wrapT, 33648);
  // One image, shared by all five texture slots.
  ASSERT_EQ(scene.images.size(), 1U);
  EXPECT_EQ(m.emissiveTexture.image, m.baseColorTexture.image);
  EXPECT_EQ(scene.images[0].pixels, (std::vector<std::uint8_t>{255, 0, 0, 255}));
}

TEST(GltfLoaderFeatures, UndecodableImageFailsOnlyWhenUsed) {
  GltfBuilder gltf;
  gltf.addNode({{"mesh", gltf.addMesh(kTriangle)}});
  const std::string garbage = "this is not an image at all";
  const int view = gltf.addView(garbage.data(), garbage.size());
  gltf.doc()["images"] = {{{"bufferView", view}, {"mimeType", "image/png"}, {"name", "broken"}}};
  const Scene unused = gltf.load();
  EXPECT_TRUE(anyWarningContains(unused, "/images/0")) << "no warning";

  gltf.doc()["textures"] = {{{"source", 0}}};
  gltf.doc()["materials"] = {{{"emissiveTexture", {{"index", 0}}}}};
  gltf.doc()["meshes"][0]["primitives"][0]["material"] = 0;
  gltf.doc()["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
      gltf.addFloats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
  const Error error = gltf.loadError();
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(error.message(), "/images/0")) << error.what();
  EXPECT_TRUE(contains(error.message(), "broken")) << error.what();
}

TEST(GltfLoaderFeatures, IndexTypesVertexColorsAndNormalizedTexcoords) {
  GltfBuilder gltf;
  const std::vector<float> quad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::uint8_t colors[16] = {255, 0, 0,   255, 0,   255, 0,   255,
                                   0,   0, 255, 255, 255, 255, 255, 0};
  const std::uint16_t uvs[8] = {0, 65535, 65535, 65535, 65535, 0, 0, 0};
  const std::uint8_t indices[6] = {0, 1, 2, 0, 2, 3};
  json attributes;
  attributes["COLOR_0"] = gltf.addAccessor({{"bufferView", gltf.addView(colors, 16)},
                                            {"componentType", 5121},
                                            {"normalized", true},
                                            {"count", 4},
                                            {"type", "VEC4"}});
  attributes["TEXCOORD_0"] = gltf.addAccessor({{"bufferView", gltf.addView(uvs, 16)},
                                               {"componentType", 5123},
                                               {"normalized", true},
                                               {"count", 4},
                                               {"type", "VEC2"}});
  const int mesh = gltf.addMesh(quad, attributes);
  gltf.doc()["meshes"][mesh]["primitives"][0]["indices"] =
      gltf.addAccessor({{"bufferView", gltf.addView(indices, 6)},
                        {"componentType", 5121},
                        {"count", 6},
                        {"type", "SCALAR"}});
  gltf.addNode({{"mesh", mesh}});
  const Scene scene = gltf.load();
  const lgh::Primitive& p = scene.meshes.at(0).primitives.at(0);
  ASSERT_EQ(p.vertices.size(), 6U);  // no NORMAL: unwelded for flat normals
  EXPECT_EQ(p.vertices[0].color, glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(p.vertices[0].uv0, glm::vec2(0, 1));
  EXPECT_EQ(p.vertices[0].normal, glm::vec3(0, 0, 1));
  // Generated tangent: u grows along +X; v grows along -Y, so the bitangent (up) is +Y: w = +1.
  EXPECT_NEAR(p.vertices[0].tangent.x, 1.0F, 1e-5F);
  EXPECT_EQ(p.vertices[0].tangent.w, 1.0F);
}

TEST(GltfLoaderFeatures, WrongAttributeFormatNamesMeshAndAttribute) {
  GltfBuilder gltf;
  json attributes;
  const std::uint8_t normals[9] = {};
  attributes["NORMAL"] = gltf.addAccessor({{"bufferView", gltf.addView(normals, 9)},
                                           {"componentType", 5121},
                                           {"count", 3},
                                           {"type", "VEC3"}});
  const int mesh = gltf.addMesh(kTriangle, attributes);
  gltf.doc()["meshes"][mesh]["name"] = "Teapot";
  gltf.addNode({{"mesh", mesh}});
  const Error error = gltf.loadError();
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(error.message(), "/meshes/0/primitives/0/attributes/NORMAL: /accessors/"))
      << error.what();
  EXPECT_TRUE(contains(error.message(), "UNSIGNED_BYTE")) << error.what();
}

TEST(GltfLoaderFeatures, AccessorPastItsBufferViewIsAnError) {
  GltfBuilder gltf;
  const int mesh = gltf.addMesh(kTriangle);
  gltf.doc()["accessors"][0]["count"] = 4;  // 48 bytes from a 36-byte view
  gltf.addNode({{"mesh", mesh}});
  const Error error = gltf.loadError();
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(error.message(),
                       "/accessors/0 (4 elements of 12 bytes, stride 12, "
                       "byteOffset 0) reaches past the end of /bufferViews/0"))
      << error.what();
}

TEST(GltfLoaderFeatures, BufferViewPastItsBufferIsAnError) {
  GltfBuilder gltf;
  const int mesh = gltf.addMesh(kTriangle);
  gltf.doc()["bufferViews"][0]["byteOffset"] = 4;  // 4 + 36 > the 36-byte buffer
  gltf.addNode({{"mesh", mesh}});
  const Error error = gltf.loadError();
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(error.message(),
                       "/bufferViews/0 (byteOffset 4, byteLength 36) reaches "
                       "past the end of /buffers/0"))
      << error.what();
}

// One mesh of triangles, lines and points: each kept, in its own list.
TEST(GltfLoaderFeatures, TrianglesLinesAndPointsOfOneMeshAreKept) {
  GltfBuilder gltf;
  const int mesh = gltf.addMesh(kTriangle);
  const json position = gltf.doc()["meshes"][mesh]["primitives"][0]["attributes"]["POSITION"];
  for (int mode : {1, 0}) {
    gltf.doc()["meshes"][mesh]["primitives"].push_back(
        {{"attributes", {{"POSITION", position}}}, {"mode", mode}});
  }
  gltf.addNode({{"mesh", mesh}});
  const Scene scene = gltf.load();
  ASSERT_EQ(scene.meshes.at(0).primitives.size(), 1U);
  ASSERT_EQ(scene.meshes.at(0).linesAndPoints.size(), 2U);
  EXPECT_EQ(scene.meshes.at(0).linesAndPoints[0].topology, lgh::Topology::Lines);
  EXPECT_EQ(scene.meshes.at(0).linesAndPoints[0].indices.size(), 2U);  // 3 vertices: one line
  EXPECT_TRUE(anyWarningContains(scene, "not a whole number of lines"));
  EXPECT_EQ(scene.meshes.at(0).linesAndPoints[1].topology, lgh::Topology::Points);
  EXPECT_EQ(scene.triangleCount(), 1U);
  EXPECT_EQ(scene.lineAndPointPrimitiveCount(), 2U);
}

TEST(GltfLoaderFeatures, SparseAccessorsAreApplied) {
  GltfBuilder gltf;
  // Base: no bufferView, so all zeros; the sparse part sets vertices 1 and 2.
  const std::uint16_t sparseIndices[2] = {1, 2};
  const float sparseValues[6] = {1, 0, 0, 0, 1, 0};
  const int indicesView = gltf.addView(sparseIndices, sizeof(sparseIndices));
  const int valuesView = gltf.addView(sparseValues, sizeof(sparseValues));
  const int positions =
      gltf.addAccessor({{"componentType", 5126},
                        {"count", 3},
                        {"type", "VEC3"},
                        {"sparse",
                         {{"count", 2},
                          {"indices", {{"bufferView", indicesView}, {"componentType", 5123}}},
                          {"values", {{"bufferView", valuesView}}}}}});
  gltf.doc()["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", positions}}}}}}});
  gltf.addNode({{"mesh", 0}});
  const Scene scene = gltf.load();
  EXPECT_EQ(scene.bounds.max, glm::vec3(1, 1, 0));
  EXPECT_EQ(scene.bounds.min, glm::vec3(0, 0, 0));
}

TEST(GltfLoaderFeatures, MeshQuantizationAllowsIntegerPositions) {
  GltfBuilder gltf;
  const std::int16_t positions[12] = {0, 0, 0, 0, 32767, 0, 0, 0, 0, 32767, 0, 0};  // padded to 8
  const int view = gltf.addView(positions, sizeof(positions));
  const int accessor = gltf.addAccessor({{"bufferView", view},
                                         {"componentType", 5122},
                                         {"normalized", true},
                                         {"count", 3},
                                         {"type", "VEC3"}});
  gltf.doc()["bufferViews"][view]["byteStride"] = 8;
  gltf.doc()["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", accessor}}}}}}});
  gltf.addNode({{"mesh", 0}});
  // Without the extension: an error naming the format.
  EXPECT_TRUE(contains(gltf.loadError().message(), "SHORT")) << "accepted";
  gltf.doc()["extensionsUsed"] = {"KHR_mesh_quantization"};
  gltf.doc()["extensionsRequired"] = {"KHR_mesh_quantization"};
  const Scene scene = gltf.load();
  EXPECT_NEAR(scene.bounds.max.x, 1.0F, 1e-6F);
  EXPECT_NEAR(scene.bounds.max.y, 1.0F, 1e-6F);
}

TEST(GltfLoaderFeatures, DegenerateUvsGiveFiniteTangents) {
  GltfBuilder gltf;
  json attributes;
  attributes["TEXCOORD_0"] = gltf.addFloats({0.5F, 0.5F, 0.5F, 0.5F, 0.5F, 0.5F}, "VEC2", 3);
  attributes["NORMAL"] = gltf.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  gltf.addNode({{"mesh", gltf.addMesh(kTriangle, attributes)}});
  const Scene scene = gltf.load();
  for (const lgh::Vertex& v : scene.meshes[0].primitives[0].vertices) {
    EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0F, 1e-5F);
    EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0F, 1e-5F);
  }
}

// ---------------------------------------------------------------------------------------------
// Mutated GLBs: each load succeeds or throws lgh::Error; nothing else, no crash.

void fuzz(const fs::path& file, std::uint32_t seed, int rounds) {
  const std::vector<std::uint8_t> original = lgh::image_io::readFile(file);
  ASSERT_GT(original.size(), 100U);
  std::mt19937 random(seed);
  int loaded = 0;
  for (int round = 0; round < rounds; ++round) {
    std::vector<std::uint8_t> bytes = original;
    const std::size_t position = random() % bytes.size();
    if (round % 4 == 3) {
      bytes.resize(position);  // truncate
    } else {
      const int flips = 1 + static_cast<int>(random() % 4);
      for (int i = 0; i < flips; ++i) {
        const std::size_t at = (position + random() % 64) % bytes.size();
        bytes[at] ^= static_cast<std::uint8_t>(1 + random() % 255);
      }
    }
    try {
      const Scene scene = lgh::loadGlbBytes(bytes, "fuzz.glb");
      EXPECT_GT(scene.triangleCount(), 0U);
      ++loaded;
    } catch (const Error& error) {
      EXPECT_FALSE(error.message().empty()) << "round " << round;
    } catch (const std::exception& error) {
      ADD_FAILURE() << "round " << round << " (position " << position
                    << ") threw a non-lgh exception: " << error.what();
    }
  }
  // Flips inside the texture or padding leave a loadable file: some rounds must load.
  EXPECT_GT(loaded, 0);
}

// ---------------------------------------------------------------------------------------------
// Extensions, poses and compressed geometry, on hand-made assets.

lgh::SceneLoadOptions animationAt(int index, float time) {
  lgh::SceneLoadOptions options;
  options.animation = lgh::SceneAnimation{index, time};
  return options;
}

Scene loadWith(GltfBuilder& gltf, const lgh::SceneLoadOptions& options) {
  return lgh::loadGltfFromMemory("model.gltf", gltf.files(), {}, options);
}

glm::vec3 worldVertex(const Scene& scene, std::size_t vertex) {
  const lgh::MeshInstance& instance = scene.instances.at(0);
  const lgh::Primitive& primitive =
      scene.meshes.at(static_cast<std::size_t>(instance.mesh)).primitives.at(0);
  return glm::vec3(instance.world * glm::vec4(primitive.vertices.at(vertex).position, 1.0F));
}

// One morph target moving every vertex +1 along Z: mesh weights, node weights, animated weights.
TEST(GltfLoaderPoses, MorphTargetsApplyTheirWeights) {
  GltfBuilder gltf;
  const int mesh = gltf.addMesh(kTriangle);
  const int target = gltf.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  gltf.doc()["meshes"][mesh]["primitives"][0]["targets"] = {{{"POSITION", target}}};
  gltf.doc()["meshes"][mesh]["weights"] = {0.25};
  const int node = gltf.addNode({{"mesh", mesh}});
  EXPECT_NEAR(worldVertex(gltf.load(), 1).z, 0.25F, 1e-6F);
  gltf.doc()["nodes"][node]["weights"] = {0.5};
  EXPECT_NEAR(worldVertex(gltf.load(), 1).z, 0.5F, 1e-6F);
  // An animation of the weights from 0 (t = 0) to 1 (t = 2), LINEAR: t = 1.5 gives 0.75.
  const int times = gltf.addFloats({0, 2}, "SCALAR", 2);
  const int values = gltf.addFloats({0, 1}, "SCALAR", 2);
  gltf.doc()["animations"] = {
      {{"samplers", {{{"input", times}, {"output", values}}}},
       {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "weights"}}}}}}}};
  EXPECT_NEAR(worldVertex(loadWith(gltf, animationAt(0, 1.5F)), 1).z, 0.75F, 1e-6F);
  // Past the end: clamped to the last key.
  EXPECT_NEAR(worldVertex(loadWith(gltf, animationAt(0, 10.0F)), 1).z, 1.0F, 1e-6F);
  const Error error = [&] {
    try {
      loadWith(gltf, animationAt(3, 0.0F));
    } catch (const Error& e) {
      return e;
    }
    return Error(ErrorCode::Internal, "loaded");
  }();
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_EQ(error.field(), "/scene/animation/index");
  EXPECT_TRUE(contains(error.message(), "1 animation(s)")) << error.what();
}

// A skin of two joints; the vertices follow joint 1, which sits 2 units up. The mesh node's own
// transform is ignored (glTF), and the skinned mesh is placed in world space.
TEST(GltfLoaderPoses, SkinsPoseTheMeshByTheirJoints) {
  GltfBuilder gltf;
  const std::vector<std::uint8_t> joints = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  const int jointsView = gltf.addView(joints.data(), joints.size());
  const int jointsAccessor = gltf.addAccessor(
      {{"bufferView", jointsView}, {"componentType", 5121}, {"count", 3}, {"type", "VEC4"}});
  const int weights = gltf.addFloats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 3);
  const int mesh = gltf.addMesh(kTriangle, {{"JOINTS_0", jointsAccessor}, {"WEIGHTS_0", weights}});
  const int root = gltf.addNode({{"translation", {0, 0, 0}}}, false);
  const int upper = gltf.addNode({{"translation", {0, 2, 0}}}, false);
  gltf.doc()["nodes"][root]["children"] = {upper};
  const std::vector<float> identity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::vector<float> bind = identity;
  bind.insert(bind.end(), identity.begin(), identity.end());
  gltf.doc()["skins"] = {
      {{"joints", {root, upper}}, {"inverseBindMatrices", gltf.addFloats(bind, "MAT4", 2)}}};
  gltf.addNode({{"mesh", mesh}, {"skin", 0}, {"translation", {100, 0, 0}}, {"children", {root}}});
  const Scene scene = gltf.load();
  EXPECT_EQ(scene.instances.at(0).world, glm::mat4(1.0F));
  // The joints hang below the skinned node (translated 100 in X), and the skin follows them.
  const glm::vec3 p = worldVertex(scene, 1);
  EXPECT_NEAR(p.x, 101.0F, 1e-5F);
  EXPECT_NEAR(p.y, 2.0F, 1e-5F);
  EXPECT_NEAR(scene.bounds.max.y, 3.0F, 1e-5F);  // vertex 2 (0, 1, 0) + 2: the posed bounds
  // A joint index past the skin's joints is named.
  gltf.doc()["skins"][0]["joints"] = {root};
  gltf.doc()["skins"][0]["inverseBindMatrices"] = gltf.addFloats(identity, "MAT4", 1);
  const Error error = gltf.loadError();
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(error.message(), "names joint 1")) << error.what();
}

// An animated translation: STEP, LINEAR and CUBICSPLINE at t = 0.5 between 0 and 10.
TEST(GltfLoaderPoses, AnimationInterpolationModes) {
  for (const auto& [mode, expected] : std::vector<std::pair<std::string, float>>{
           {"STEP", 0.0F}, {"LINEAR", 5.0F}, {"CUBICSPLINE", 5.0F}}) {
    SCOPED_TRACE(mode);
    GltfBuilder gltf;
    const int node = gltf.addNode({{"mesh", gltf.addMesh(kTriangle)}});
    const int times = gltf.addFloats({0, 1}, "SCALAR", 2);
    // CUBICSPLINE: in-tangent, value, out-tangent per key (zero tangents: smoothstep, 5 at t=0.5).
    const int values =
        mode == "CUBICSPLINE"
            ? gltf.addFloats({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 10, 0, 0, 0}, "VEC3", 6)
            : gltf.addFloats({0, 0, 0, 0, 0, 10}, "VEC3", 2);
    gltf.doc()["animations"] = {
        {{"samplers", {{{"input", times}, {"output", values}, {"interpolation", mode}}}},
         {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}}}}}};
    const Scene scene = loadWith(gltf, animationAt(0, 0.5F));
    EXPECT_NEAR(scene.instances.at(0).world[3].z, expected, 1e-4F);
  }
}

TEST(GltfLoaderPoses, SampleAssetsPose) {
  // AnimatedMorphCube: the bind pose has weights 0; its animation moves the morph targets.
  const fs::path cube =
      models() / "glTF-Sample-Models" / "AnimatedMorphCube-glTF" / "AnimatedMorphCube.gltf";
  const Scene rest = loadFile(cube);
  const Scene posed =
      lgh::loadGltfFile(cube.parent_path(), cube.filename().string(), {}, animationAt(0, 1.0F));
  EXPECT_GT(glm::distance(rest.bounds.max, posed.bounds.max), 1e-3F);
  // simple_skin: skinned at the bind pose; posed at 1 s the bounds differ.
  const fs::path skin = models() / "simple_skin" / "simple_skin.gltf";
  const Scene skinRest = loadFile(skin);
  EXPECT_FALSE(anyWarningContains(skinRest, "skin"));
  const Scene skinPosed =
      lgh::loadGltfFile(skin.parent_path(), skin.filename().string(), {}, animationAt(0, 1.0F));
  EXPECT_GT(glm::distance(skinRest.bounds.max, skinPosed.bounds.max), 1e-3F);
}

TEST(GltfLoaderExtensions, MaterialVariantsChooseTheMaterial) {
  GltfBuilder gltf;
  const int mesh = gltf.addMesh(kTriangle);
  gltf.doc()["materials"] = {{{"name", "plain"}}, {{"name", "red"}}};
  gltf.doc()["meshes"][mesh]["primitives"][0]["material"] = 0;
  gltf.doc()["meshes"][mesh]["primitives"][0]["extensions"]["KHR_materials_variants"] = {
      {"mappings", {{{"material", 1}, {"variants", {1}}}}}};
  gltf.doc()["extensionsUsed"] = {"KHR_materials_variants"};
  gltf.doc()["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "blue"}},
                                                                    {{"name", "red"}}};
  gltf.addNode({{"mesh", mesh}});
  EXPECT_EQ(gltf.load().meshes.at(0).primitives.at(0).material, 0);
  lgh::SceneLoadOptions options;
  options.materialVariant = "red";
  EXPECT_EQ(loadWith(gltf, options).meshes.at(0).primitives.at(0).material, 1);
  options.materialVariant = "blue";  // no mapping for blue: the default material
  EXPECT_EQ(loadWith(gltf, options).meshes.at(0).primitives.at(0).material, 0);
  options.materialVariant = "green";
  try {
    loadWith(gltf, options);
    ADD_FAILURE() << "loaded";
  } catch (const Error& error) {
    EXPECT_EQ(error.field(), "/scene/material_variant");
    EXPECT_TRUE(contains(error.message(), "it has: blue, red")) << error.what();
  }
}

TEST(GltfLoaderExtensions, MaterialExtensionsAreRead) {
  GltfBuilder gltf;
  const int mesh = gltf.addMesh(kTriangle);
  gltf.doc()["materials"] = {
      {{"extensions",
        {{"KHR_materials_sheen",
          {{"sheenColorFactor", {1, 0.5, 0}}, {"sheenRoughnessFactor", 0.3}}},
         {"KHR_materials_specular", {{"specularFactor", 0.5}, {"specularColorFactor", {1, 0, 0}}}},
         {"KHR_materials_ior", {{"ior", 1.33}}},
         {"KHR_materials_transmission", {{"transmissionFactor", 0.8}}},
         {"KHR_materials_volume",
          {{"thicknessFactor", 1}, {"attenuationDistance", 1}, {"attenuationColor", {0.5, 1, 1}}}},
         {"KHR_materials_clearcoat",
          {{"clearcoatFactor", 2}, {"clearcoatRoughnessFactor", 0.2}}}}}},
      {{"extensions", {{"KHR_materials_unlit", json::object()}}}}};
  gltf.doc()["meshes"][mesh]["primitives"][0]["material"] = 0;
  gltf.doc()["extensionsUsed"] = {"KHR_materials_sheen",  "KHR_materials_specular",
                                  "KHR_materials_ior",    "KHR_materials_transmission",
                                  "KHR_materials_volume", "KHR_materials_clearcoat",
                                  "KHR_materials_unlit"};
  gltf.addNode({{"mesh", mesh}});
  const Scene scene = gltf.load();
  const lgh::Material& m = scene.materials.at(0);
  EXPECT_EQ(m.sheen.colorFactor, glm::vec3(1, 0.5, 0));
  EXPECT_FLOAT_EQ(m.sheen.roughnessFactor, 0.3F);
  EXPECT_FLOAT_EQ(m.specular.factor, 0.5F);
  EXPECT_EQ(m.specular.colorFactor, glm::vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(m.specular.ior, 1.33F);
  EXPECT_FLOAT_EQ(m.transmission.factor, 0.8F);
  EXPECT_NEAR(m.transmission.tint().r, 0.5F, 1e-6F);  // one attenuation distance thick
  EXPECT_FLOAT_EQ(m.clearcoat.factor, 1.0F);          // clamped to [0, 1]
  EXPECT_TRUE(m.hasLayers());
  EXPECT_EQ(scene.materials.at(1).model, lgh::MaterialModel::Unlit);
  EXPECT_FALSE(scene.materials.at(1).hasLayers());
}

// KHR_texture_transform: the matrix is T * R * S of the extension's reference code.
TEST(GltfLoaderExtensions, TextureTransformMatrix) {
  lgh::UvTransform t;
  t.offset = {0.5F, 0.25F};
  t.rotation = 0.3F;
  t.scale = {2.0F, 3.0F};
  const glm::vec2 uv(0.2F, 0.7F);
  const glm::vec2 scaled = uv * t.scale;
  const float c = std::cos(t.rotation);
  const float s = std::sin(t.rotation);
  // Rotation as KHR_texture_transform's reference: u' = c u + s v, v' = -s u + c v.
  const glm::vec2 expected(c * scaled.x + s * scaled.y + 0.5F,
                           -s * scaled.x + c * scaled.y + 0.25F);
  const glm::vec2 got = t.matrix() * glm::vec3(uv, 1.0F);
  EXPECT_NEAR(got.x, expected.x, 1e-6F);
  EXPECT_NEAR(got.y, expected.y, 1e-6F);
}

// KHR_texture_basisu: no transcoder here. Required, it is refused by name; optional, the
// texture's plain source is used.
TEST(GltfLoaderExtensions, BasisuIsRefusedOrFallsBack) {
  GltfBuilder gltf;
  gltf.addNode({{"mesh", gltf.addMesh(kTriangle)}});
  gltf.doc()["extensionsUsed"] = {"KHR_texture_basisu"};
  gltf.doc()["extensionsRequired"] = {"KHR_texture_basisu"};
  const Error error = gltf.loadError();
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(error.message(), "KHR_texture_basisu")) << error.what();
  gltf.doc().erase("extensionsRequired");
  EXPECT_TRUE(anyWarningContains(gltf.load(), "KHR_texture_basisu"));
}

// EXT_meshopt_compression: a quad's vertices and indices encoded with meshoptimizer decode to the
// same scene as the plain asset; a corrupted stream is a named error.
TEST(GltfLoaderCompression, MeshoptDecodesToThePlainGeometry) {
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
  std::vector<unsigned char> vertexStream(meshopt_encodeVertexBufferBound(4, 12));
  vertexStream.resize(meshopt_encodeVertexBuffer(vertexStream.data(), vertexStream.size(),
                                                 positions.data(), 4, 12));
  std::vector<unsigned char> indexStream(meshopt_encodeIndexBufferBound(6, 4));
  indexStream.resize(
      meshopt_encodeIndexBuffer(indexStream.data(), indexStream.size(), indices.data(), 6));
  auto build = [&](bool corrupt) {
    GltfBuilder gltf;
    std::vector<unsigned char> vertices = vertexStream;
    if (corrupt) vertices.assign(vertices.size(), 0xFF);
    // Compressed bytes in views 0 and 1; the views the accessors read (2 and 3) name them.
    const int compressedVertices = gltf.addView(vertices.data(), vertices.size());
    const int compressedIndices = gltf.addView(indexStream.data(), indexStream.size());
    const std::vector<unsigned char> placeholder(48, 0);
    const int vertexView = gltf.addView(placeholder.data(), 48);
    const int indexView = gltf.addView(placeholder.data(), 24);
    auto meshopt = [&](int source, int stride, int count, const char* mode) {
      const json& view = gltf.doc()["bufferViews"][source];
      return json{{"EXT_meshopt_compression",
                   {{"buffer", 0},
                    {"byteOffset", view["byteOffset"]},
                    {"byteLength", view["byteLength"]},
                    {"byteStride", stride},
                    {"count", count},
                    {"mode", mode}}}};
    };
    gltf.doc()["bufferViews"][vertexView]["byteStride"] = 12;
    gltf.doc()["bufferViews"][vertexView]["extensions"] =
        meshopt(compressedVertices, 12, 4, "ATTRIBUTES");
    gltf.doc()["bufferViews"][indexView]["extensions"] =
        meshopt(compressedIndices, 4, 6, "TRIANGLES");
    const int position = gltf.addAccessor({{"bufferView", vertexView},
                                           {"componentType", 5126},
                                           {"count", 4},
                                           {"type", "VEC3"},
                                           {"min", {0, 0, 0}},
                                           {"max", {1, 1, 0}}});
    const int index = gltf.addAccessor(
        {{"bufferView", indexView}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}});
    gltf.doc()["meshes"] = {
        {{"primitives", {{{"attributes", {{"POSITION", position}}}, {"indices", index}}}}}};
    gltf.addNode({{"mesh", 0}});
    gltf.doc()["extensionsUsed"] = {"EXT_meshopt_compression"};
    gltf.doc()["extensionsRequired"] = {"EXT_meshopt_compression"};
    return gltf;
  };
  GltfBuilder good = build(false);
  const Scene scene = good.load();
  ASSERT_EQ(scene.triangleCount(), 2U);
  const lgh::Primitive& primitive = scene.meshes.at(0).primitives.at(0);
  // No NORMAL: flat normals unweld the quad; the positions are the encoded ones.
  ASSERT_EQ(primitive.indices.size(), 6U);
  for (std::size_t i = 0; i < 6; ++i) {
    const glm::vec3 p = primitive.vertices[primitive.indices[i]].position;
    const float* expected = &positions[indices[i] * 3];
    EXPECT_EQ(p, glm::vec3(expected[0], expected[1], expected[2])) << i;
  }
  GltfBuilder bad = build(true);
  const Error error = bad.loadError();
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(error.message(), "does not decode")) << error.what();
}

// A Draco stream of garbage bytes is a named error, not a crash.
TEST(GltfLoaderCompression, HostileDracoStreamIsAnError) {
  GltfBuilder gltf;
  const int mesh = gltf.addMesh(kTriangle);
  const std::vector<std::uint8_t> garbage(64, 0x5A);
  const int view = gltf.addView(garbage.data(), garbage.size());
  gltf.doc()["meshes"][mesh]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {
      {"bufferView", view}, {"attributes", {{"POSITION", 0}}}};
  gltf.doc()["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  gltf.doc()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  gltf.addNode({{"mesh", mesh}});
  const Error error = gltf.loadError();
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_TRUE(contains(error.message(), "Draco stream does not decode")) << error.what();
}

// EXT_texture_webp: a lossless 2x1 WebP (red, green) decodes to the same pixels.
TEST(GltfLoaderExtensions, WebpTexturesDecode) {
  const std::uint8_t rgba[8] = {255, 0, 0, 255, 0, 255, 0, 255};
  std::uint8_t* encoded = nullptr;
  const std::size_t size = WebPEncodeLosslessRGBA(rgba, 2, 1, 8, &encoded);
  ASSERT_GT(size, 0U);
  GltfBuilder gltf;
  const int view = gltf.addView(encoded, size);
  WebPFree(encoded);
  const int mesh =
      gltf.addMesh(kTriangle, {{"TEXCOORD_0", gltf.addFloats({0, 0, 1, 0, 0, 1}, "VEC2", 3)}});
  gltf.doc()["images"] = {{{"bufferView", view}, {"mimeType", "image/webp"}}};
  gltf.doc()["textures"] = {{{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}};
  gltf.doc()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  gltf.doc()["meshes"][mesh]["primitives"][0]["material"] = 0;
  gltf.doc()["extensionsUsed"] = {"EXT_texture_webp"};
  gltf.doc()["extensionsRequired"] = {"EXT_texture_webp"};
  gltf.addNode({{"mesh", mesh}});
  const Scene scene = gltf.load();
  ASSERT_EQ(scene.images.size(), 1U);
  EXPECT_EQ(scene.images[0].width, 2);
  EXPECT_EQ(std::vector<std::uint8_t>(scene.images[0].pixels.begin(), scene.images[0].pixels.end()),
            std::vector<std::uint8_t>(rgba, rgba + 8));
}

TEST(GltfLoaderFuzz, MutatedTexturedBox) {
  fuzz(models() / "BoxTextured-glTF-Binary" / "BoxTextured.glb", 20240601U, 200);
}

TEST(GltfLoaderFuzz, MutatedBadNormalsBox) {
  fuzz(models() / "BoxBadNormals-glTF-Binary" / "BoxBadNormals.glb", 7U, 200);
}

}  // namespace
