// Real-world glTF coverage through the real daemon: every glTF 2.0 file of Debian's
// assimp-testmodels that the Khronos glTF validator passes renders without error and not blank.
// The run prints one line per file (status, coverage, warnings) for the record.
//
// The expectation, tests/http/gltf_validator_clean.txt, lists the files with no validator error
// (how it was made is written at its top); nothing else of the validator's is kept.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "http_helpers.hpp"

namespace lghd::test {
namespace {

// tests/http/gltf_validator_clean.txt: one asset path per line, # comments.
std::vector<std::string> validatorClean() {
  std::vector<std::string> assets;
  std::istringstream lines(
      readFile(std::filesystem::path(LGH_HTTP_TEST_DIR) / "gltf_validator_clean.txt"));
  std::string line;
  while (std::getline(lines, line)) {
    if (!line.empty() && line[0] != '#') assets.push_back(line);
  }
  return assets;
}

// A valid asset with nothing to draw (a scene without nodes): it renders, blank by definition.
const std::string kEmptyScene = "TestNoRootNode/SceneWithoutNodes.gltf";
// Valid, but requires KHR_technique_webgl (glTF 1.0's materials): refused by default, rendered
// with settings.ignore_unsupported_extensions.
const std::string kLegacyRequired = "BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf";

constexpr int kSize = 64;

// Pixels whose alpha is not 0: with a transparent background, what the asset covers.
int coveredPixels(const lgh::image_io::Decoded& image) {
  int covered = 0;
  for (std::size_t i = 3; i < image.pixels8.size(); i += 4) {
    covered += image.pixels8[i] != 0 ? 1 : 0;
  }
  return covered;
}

class GltfCoverageTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { daemon = new DaemonProcess(); }
  static void TearDownTestSuite() {
    delete daemon;
    daemon = nullptr;
  }
  void SetUp() override { http = daemon->client(std::chrono::seconds(300)); }
  void TearDown() override {
    if (HasFailure()) std::cerr << "--- lghd log ---\n" << daemon->log();
  }

  httplib::Result render(const std::string& asset, bool ignoreUnsupported) {
    const json request = {
        {"scene", {{"asset", asset}}},
        {"camera", {{"type", "auto"}}},
        {"output", {{"width", kSize}, {"height", kSize}, {"transparent_background", true}}},
        {"settings", {{"ignore_unsupported_extensions", ignoreUnsupported}, {"shadows", "off"}}}};
    return postJson(*http, "/v1/render", request);
  }

  static DaemonProcess* daemon;
  std::unique_ptr<httplib::Client> http;
};
DaemonProcess* GltfCoverageTest::daemon = nullptr;

TEST_F(GltfCoverageTest, EveryValidatorCleanAssetRendersAndIsNotBlank) {
  const std::vector<std::string> assets = validatorClean();
  ASSERT_EQ(assets.size(), 29U);
  int rendered = 0;
  for (const std::string& asset : assets) {
    SCOPED_TRACE(asset);
    const bool legacy = asset == kLegacyRequired;
    const auto result = render(asset, legacy);
    ASSERT_TRUE(result);
    const int covered = result->status == 200 ? coveredPixels(decodeBody(result->body, asset)) : 0;
    std::printf("gltf-coverage %-70s status %d  covered %4d of %d px  warnings %s\n", asset.c_str(),
                result->status, covered, kSize * kSize,
                result->get_header_value("X-Lgh-Warnings").size() > 2 ? "yes" : "-");
    EXPECT_EQ(result->status, 200) << result->body;
    if (result->status != 200) continue;
    ++rendered;
    if (asset == kEmptyScene) {
      EXPECT_EQ(covered, 0);
    } else {
      // Not blank: the asset covers a visible share of the frame (the auto camera frames it).
      EXPECT_GT(covered, kSize * kSize / 100) << "blank render";
    }
  }
  std::printf("gltf-coverage: %d of %zu validator-clean assets rendered\n", rendered,
              assets.size());
}

TEST_F(GltfCoverageTest, RequiredUnsupportedExtensionIsA422NamingIt) {
  const auto result = render(kLegacyRequired, false);
  ASSERT_TRUE(result);
  const json error = expectError(result, 422, "invalid");
  EXPECT_NE(error["message"].get<std::string>().find("KHR_technique_webgl"), std::string::npos)
      << error.dump();
}

// scene.animation through the daemon: the posed skin renders, and an animation the asset lacks is
// a 422 naming the field.
TEST_F(GltfCoverageTest, AnimationPoseAndItsErrors) {
  json request = {
      {"scene",
       {{"asset", "simple_skin/simple_skin.gltf"}, {"animation", {{"index", 0}, {"time", 1.5}}}}},
      {"output", {{"width", 32}, {"height", 32}}},
      {"settings", {{"shadows", "off"}}}};
  auto result = postJson(*http, "/v1/render", request);
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 200) << result->body;
  request["scene"]["animation"]["index"] = 4;
  result = postJson(*http, "/v1/render", request);
  ASSERT_TRUE(result);
  const json error = expectError(result, 422, "invalid");
  EXPECT_EQ(error["field"], "/scene/animation/index");
}

}  // namespace
}  // namespace lghd::test
