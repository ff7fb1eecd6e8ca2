// The asset sandbox: resolveAssetPath on its own, and the glTF loader's use of it for the URIs
// inside an asset (buffers and images), on disk and in memory.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "lgh/error.hpp"
#include "scene/asset_path.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using lgh::Error;
using lgh::ErrorCode;

void writeFile(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::vector<std::uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

// One triangle: three float VEC3 positions, 36 bytes.
std::string triangleBin() {
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::string bin(sizeof(positions), '\0');
  std::memcpy(bin.data(), positions, sizeof(positions));
  return bin;
}

// A one-triangle glTF whose buffer lives at `bufferUri`; with `imageUri`, a textured material.
std::string triangleGltf(const std::string& bufferUri, const std::string& imageUri = "") {
  nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", 36}}}},
      {"buffers", {{{"uri", bufferUri}, {"byteLength", 36}}}},
  };
  if (!imageUri.empty()) {
    gltf["images"] = {{{"uri", imageUri}}};
    gltf["textures"] = {{{"source", 0}}};
    gltf["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    gltf["meshes"][0]["primitives"][0]["material"] = 0;
    // The texture coordinates the material samples (the first 24 bytes of the buffer).
    gltf["bufferViews"].push_back({{"buffer", 0}, {"byteLength", 24}});
    gltf["accessors"].push_back(
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
    gltf["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 1;
  }
  return gltf.dump();
}

// A GLB with only a JSON chunk (its buffer must then come from a URI).
std::vector<std::uint8_t> glbWithJsonOnly(std::string json) {
  while (json.size() % 4 != 0) json += ' ';
  std::vector<std::uint8_t> glb;
  auto put32 = [&](std::uint32_t value) {
    for (int i = 0; i < 4; ++i) glb.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
  };
  put32(0x46546C67);
  put32(2);
  put32(static_cast<std::uint32_t>(20 + json.size()));
  put32(static_cast<std::uint32_t>(json.size()));
  put32(0x4E4F534A);
  glb.insert(glb.end(), json.begin(), json.end());
  return glb;
}

// <test-output>/asset_path/<test>/{root, outside, secret.bin}, with symlinks inside root that
// point outside it (escape, link.bin) and one that stays inside (inner.bin).
class AssetSandbox : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    base_ = lgh::test::outputDir() / "asset_path" / info->name();
    fs::remove_all(base_);
    root_ = base_ / "root";
    fs::create_directories(root_ / "sub");
    fs::create_directories(base_ / "outside");
    writeFile(root_ / "a.gltf", triangleGltf("sub/tri.bin"));
    writeFile(root_ / "sub" / "tri.bin", triangleBin());
    writeFile(base_ / "secret.bin", triangleBin());
    writeFile(base_ / "outside" / "secret.bin", triangleBin());
    fs::create_directory_symlink(base_ / "outside", root_ / "escape");
    fs::create_symlink(base_ / "outside" / "secret.bin", root_ / "link.bin");
    fs::create_symlink("sub/tri.bin", root_ / "inner.bin");
  }

  // The code of the lgh::Error that `resolveAssetPath(root_, relative)` throws.
  ErrorCode resolveError(const std::string& relative) {
    try {
      lgh::resolveAssetPath(root_, relative, "/scene/asset");
    } catch (const Error& error) {
      EXPECT_EQ(error.field(), "/scene/asset");
      EXPECT_FALSE(error.message().empty());
      return error.code();
    }
    ADD_FAILURE() << "'" << relative << "' was accepted";
    return ErrorCode::Internal;
  }

  // The lgh::Error that loading `relative` (a glTF under root_) throws.
  Error loadError(const std::string& relative) {
    try {
      lgh::loadGltfFile(root_, relative);
    } catch (const Error& error) {
      return error;
    }
    ADD_FAILURE() << relative << " loaded";
    return Error(ErrorCode::Internal, "loaded");
  }

  fs::path base_;
  fs::path root_;
};

TEST_F(AssetSandbox, ResolvesPathsInsideTheRoot) {
  const fs::path tri = fs::canonical(root_ / "sub" / "tri.bin");
  EXPECT_EQ(lgh::resolveAssetPath(root_, "a.gltf", "f"), fs::canonical(root_ / "a.gltf"));
  EXPECT_EQ(lgh::resolveAssetPath(root_, "sub/tri.bin", "f"), tri);
  EXPECT_EQ(lgh::resolveAssetPath(root_, "./sub//tri.bin", "f"), tri);
  // A symlink whose target stays inside the root is fine.
  EXPECT_EQ(lgh::resolveAssetPath(root_, "inner.bin", "f"), tri);
}

TEST_F(AssetSandbox, RejectsMalformedPaths) {
  EXPECT_EQ(resolveError(""), ErrorCode::BadRequest);
  EXPECT_EQ(resolveError(std::string("a.gltf\0.png", 11)), ErrorCode::BadRequest);
  EXPECT_EQ(resolveError("/etc/passwd"), ErrorCode::BadRequest);
  EXPECT_EQ(resolveError((root_ / "a.gltf").string()), ErrorCode::BadRequest);  // absolute
  EXPECT_EQ(resolveError("."), ErrorCode::BadRequest);
}

TEST_F(AssetSandbox, RejectsDotDotEvenWhenItStaysInside) {
  EXPECT_EQ(resolveError("../secret.bin"), ErrorCode::BadRequest);
  EXPECT_EQ(resolveError("sub/../a.gltf"), ErrorCode::BadRequest);
  EXPECT_EQ(resolveError("sub/../../secret.bin"), ErrorCode::BadRequest);
}

TEST_F(AssetSandbox, RejectsSymlinksLeavingTheRoot) {
  EXPECT_EQ(resolveError("escape/secret.bin"), ErrorCode::BadRequest);
  EXPECT_EQ(resolveError("link.bin"), ErrorCode::BadRequest);
  // Even when the target does not exist: no probing outside the root.
  EXPECT_EQ(resolveError("escape/nothing.bin"), ErrorCode::BadRequest);
}

TEST_F(AssetSandbox, MissingFileIsNotFoundNamingIt) {
  try {
    lgh::resolveAssetPath(root_, "models/nope.gltf", "/scene/asset");
    FAIL() << "accepted";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::NotFound);
    EXPECT_NE(error.message().find("models/nope.gltf"), std::string::npos) << error.what();
    // The server's absolute path is not echoed back.
    EXPECT_EQ(error.message().find(root_.string()), std::string::npos) << error.what();
  }
}

TEST_F(AssetSandbox, DirectoryIsNotAnAsset) {
  EXPECT_EQ(resolveError("sub"), ErrorCode::BadRequest);
}

TEST_F(AssetSandbox, GltfWithSideFilesInsideLoads) {
  const lgh::Scene scene = lgh::loadGltfFile(root_, "a.gltf");
  EXPECT_EQ(scene.triangleCount(), 1U);
  // URIs are relative to the glTF's own folder.
  writeFile(root_ / "sub" / "b.gltf", triangleGltf("tri.bin"));
  EXPECT_EQ(lgh::loadGltfFile(root_, "sub/b.gltf").triangleCount(), 1U);
}

TEST_F(AssetSandbox, TopLevelAssetGoesThroughTheSandbox) {
  EXPECT_EQ(loadError("../secret.bin").code(), ErrorCode::BadRequest);
  EXPECT_EQ(loadError("escape/secret.bin").code(), ErrorCode::BadRequest);
  EXPECT_EQ(loadError("missing.gltf").code(), ErrorCode::NotFound);
}

TEST_F(AssetSandbox, BufferUriWithDotDotIsRejected) {
  writeFile(root_ / "evil.gltf", triangleGltf("../secret.bin"));
  const Error error = loadError("evil.gltf");
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_NE(error.message().find("../secret.bin"), std::string::npos) << error.what();
  EXPECT_EQ(error.field(), "evil.gltf");
}

TEST_F(AssetSandbox, PercentEncodedDotDotIsRejected) {
  writeFile(root_ / "evil.gltf", triangleGltf("%2e%2e/secret.bin"));
  EXPECT_EQ(loadError("evil.gltf").code(), ErrorCode::Invalid);
}

TEST_F(AssetSandbox, AbsoluteAndSchemeUrisAreRejected) {
  writeFile(root_ / "absolute.gltf", triangleGltf((base_ / "secret.bin").string()));
  EXPECT_EQ(loadError("absolute.gltf").code(), ErrorCode::Invalid);
  writeFile(root_ / "scheme.gltf", triangleGltf("file:///etc/passwd"));
  EXPECT_EQ(loadError("scheme.gltf").code(), ErrorCode::Invalid);
}

TEST_F(AssetSandbox, BufferUriThroughEscapingSymlinkIsRejected) {
  writeFile(root_ / "evil.gltf", triangleGltf("link.bin"));
  EXPECT_EQ(loadError("evil.gltf").code(), ErrorCode::Invalid);
  writeFile(root_ / "evil2.gltf", triangleGltf("escape/secret.bin"));
  EXPECT_EQ(loadError("evil2.gltf").code(), ErrorCode::Invalid);
}

TEST_F(AssetSandbox, ImageUriEscapeFailsTheLoad) {
  writeFile(base_ / "secret.png", "not a png");
  writeFile(root_ / "evil.gltf", triangleGltf("sub/tri.bin", "../secret.png"));
  const Error error = loadError("evil.gltf");
  EXPECT_EQ(error.code(), ErrorCode::Invalid);
  EXPECT_NE(error.message().find("../secret.png"), std::string::npos) << error.what();
}

TEST_F(AssetSandbox, MissingBufferIsNotFound) {
  writeFile(root_ / "missing.gltf", triangleGltf("sub/gone.bin"));
  const Error error = loadError("missing.gltf");
  EXPECT_EQ(error.code(), ErrorCode::NotFound);
  EXPECT_NE(error.message().find("sub/gone.bin"), std::string::npos) << error.what();
}

TEST(AssetSandboxMemory, UploadedGltfResolvesOnlyUploadedNames) {
  const std::map<std::string, std::vector<std::uint8_t>> good = {
      {"model/scene.gltf", bytesOf(triangleGltf("tri.bin"))},
      {"model/tri.bin", bytesOf(triangleBin())}};
  EXPECT_EQ(lgh::loadGltfFromMemory("model/scene.gltf", good).triangleCount(), 1U);

  const std::map<std::string, std::vector<std::uint8_t>> evil = {
      {"scene.gltf", bytesOf(triangleGltf("../secret.bin"))},
      {"../secret.bin", bytesOf(triangleBin())}};
  try {
    lgh::loadGltfFromMemory("scene.gltf", evil);
    FAIL() << "loaded";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::Invalid) << error.what();
  }

  const std::map<std::string, std::vector<std::uint8_t>> missing = {
      {"scene.gltf", bytesOf(triangleGltf("tri.bin"))}};
  try {
    lgh::loadGltfFromMemory("scene.gltf", missing);
    FAIL() << "loaded";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::NotFound) << error.what();
    EXPECT_NE(error.message().find("tri.bin"), std::string::npos) << error.what();
  }
  EXPECT_THROW(lgh::loadGltfFromMemory("other.gltf", missing), Error);
}

TEST(AssetSandboxMemory, InlineGlbCannotReferenceFiles) {
  try {
    lgh::loadGlbBytes(glbWithJsonOnly(triangleGltf("tri.bin")), "inline.glb");
    FAIL() << "loaded";
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::Invalid) << error.what();
    EXPECT_NE(error.message().find("tri.bin"), std::string::npos) << error.what();
  }
}

}  // namespace
