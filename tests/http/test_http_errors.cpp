// Every error path of the daemon, each answered with the JSON error body and the right status;
// after each one the daemon still answers /healthz and renders correctly.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <thread>

#include "daemon_process.hpp"
#include "http_helpers.hpp"

namespace lghd::test {
namespace {

// The daemon's own path must not appear in messages.
std::string daemon_root() { return assetRoot().root.string(); }

class ErrorsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    daemon = new DaemonProcess({"--max-body-mb", "2", "--max-pixels", "1048576", "--max-vpls",
                                "1000", "--max-triangles", "2000", "--max-texture-size", "64"});
  }
  static void TearDownTestSuite() {
    delete daemon;
    daemon = nullptr;
  }
  void SetUp() override { http = daemon->client(); }
  void TearDown() override {
    expectStillHealthy();
    if (HasFailure()) std::cerr << "--- lghd log ---\n" << daemon->log();
  }

  void expectStillHealthy() {
    const auto health = http->Get("/healthz");
    ASSERT_TRUE(health);
    EXPECT_EQ(health->status, 200);
    const json request = {{"output", {{"width", 32}, {"height", 24}}}};
    const auto render = postJson(*http, "/v1/render", request);
    ASSERT_TRUE(render);
    ASSERT_EQ(render->status, 200) << render->body;
    const auto image = decodeBody(render->body);
    EXPECT_EQ(image.width, 32);
    EXPECT_EQ(image.height, 24);
  }

  json renderError(const json& request, int status, const std::string& code) {
    return expectError(postJson(*http, "/v1/render", request), status, code);
  }

  static DaemonProcess* daemon;
  std::unique_ptr<httplib::Client> http;
};
DaemonProcess* ErrorsTest::daemon = nullptr;

json withAsset(const std::string& path) {
  return {{"scene", {{"asset", path}}}, {"output", {{"width", 32}, {"height", 32}}}};
}

TEST_F(ErrorsTest, MalformedJsonIs400) {
  expectError(http->Post("/v1/render", "{\"output\": ", "application/json"), 400, "bad_request");
  expectError(http->Post("/v1/render", "[1, 2]", "application/json"), 400, "bad_request");
  const json error = renderError({{"outptu", {{"width", 32}}}}, 400, "bad_request");
  EXPECT_FALSE(error["field"].is_null());
}

TEST_F(ErrorsTest, NanInTheCameraIsRefused) {
  // JSON has no NaN: the literal is malformed (400); a number overflowing a double is named.
  expectError(
      http->Post("/v1/render", R"({"camera": {"type": "look_at", "position": [0, NaN, 4]}})",
                 "application/json"),
      400, "bad_request");
  const auto result =
      http->Post("/v1/render", R"({"camera": {"type": "look_at", "position": [0, 1e999, 4]}})",
                 "application/json");
  const json error = expectError(result, 422, "invalid");
  EXPECT_EQ(error["field"], "/camera/position/1");
}

TEST_F(ErrorsTest, SemanticallyInvalidCameraIs422) {
  const json request = {
      {"camera", {{"type", "look_at"}, {"position", {1, 1, 1}}, {"target", {1, 1, 1}}}}};
  renderError(request, 422, "invalid");
}

TEST_F(ErrorsTest, LimitsAre413) {
  EXPECT_EQ(renderError({{"output", {{"width", 5000}, {"height", 10}}}}, 413, "too_large")["field"],
            "/output/width");
  EXPECT_EQ(
      renderError({{"output", {{"width", 2048}, {"height", 1024}}}}, 413, "too_large")["field"],
      "/output");
  EXPECT_EQ(renderError({{"settings", {{"lgh", {{"enabled", true}, {"vpl_count", 5000}}}}}}, 413,
                        "too_large")["field"],
            "/settings/lgh/vpl_count");
}

// The lecture's material parameters: shape errors 400, ranges and meaning 422, each naming the
// field; those that need the scene (a material name, a texture index) are found at render time.
TEST_F(ErrorsTest, BadMaterialParametersNameTheField) {
  auto material = [](const json& match, const json& parameters) {
    return json{{"materials", {{{"match", match}, {"parameters", parameters}}}},
                {"output", {{"width", 32}, {"height", 24}}}};
  };
  const json red = {{"name", "red"}};
  EXPECT_EQ(renderError(material(red, {{"shininess", 5000}}), 422, "invalid")["field"],
            "/materials/0/parameters/shininess");
  EXPECT_EQ(renderError(material(red, {{"model", "ward"}}), 400, "bad_request")["field"],
            "/materials/0/parameters/model");
  EXPECT_EQ(renderError(material({{"name", "marble"}}, json::object()), 422, "invalid")["field"],
            "/materials/0/match/name");
  EXPECT_EQ(renderError(material(red, {{"shading", "gouraud"}}), 422, "invalid")["field"],
            "/materials/0/parameters/shading");
  EXPECT_EQ(renderError(material(red, {{"surface", "relief"}}), 422, "invalid")["field"],
            "/materials/0/parameters/surface");
  EXPECT_EQ(
      renderError(material(red, {{"height_texture", {{"texture", 40}}}}), 422, "invalid")["field"],
      "/materials/0/parameters/height_texture/texture");
}

TEST_F(ErrorsTest, TooManyTrianglesIs413) {
  renderError(withAsset("2CylinderEngine-glTF-Binary/2CylinderEngine.glb"), 413, "too_large");
}

TEST_F(ErrorsTest, TextureOverTheLimitIs413) {
  renderError(withAsset("BoxTextured-glTF-Binary/BoxTextured.glb"), 413, "too_large");
}

TEST_F(ErrorsTest, OversizedBodyIs413WithOurJson) {
  const std::string body = "{\"pad\": \"" + std::string(3 << 20, 'x') + "\"}";
  const auto result = http->Post("/v1/render", body, "application/json");
  const json error = expectError(result, 413, "too_large");
  EXPECT_NE(error["message"].get<std::string>().find("2097152"), std::string::npos);
  EXPECT_FALSE(result->get_header_value("X-Request-Id").empty());
}

TEST_F(ErrorsTest, ChunkedBodyIs411AndNotReadWhole) {
  // A chunked body has no length for httplib's limit: lghd refuses it before reading it.
  std::size_t sent = 0;
  const auto result = http->Post(
      "/v1/render",
      [&sent](std::size_t /*offset*/, httplib::DataSink& sink) {
        const std::string chunk(64 << 10, 'x');
        if (sent >= (64U << 20)) {
          sink.done();
          return true;
        }
        sent += chunk.size();
        return sink.write(chunk.data(), chunk.size());
      },
      "application/json");
  if (result) {  // the answer may come before the client notices the closed connection
    const json error = expectError(result, 411, "length_required");
    EXPECT_EQ(error["field"], "Transfer-Encoding");
  }
  EXPECT_LT(sent, 64U << 20) << "the daemon read the whole chunked body";
}

TEST_F(ErrorsTest, OversizedUploadIs413) {
  httplib::MultipartFormDataItems items{
      requestPart(json::object()),
      {"file", std::string(3 << 20, 'g'), "big.glb", "application/octet-stream"}};
  expectError(http->Post("/v1/render", items), 413, "too_large");
}

TEST_F(ErrorsTest, UnknownAssetIs404) {
  const json error = renderError(withAsset("no/such/model.glb"), 404, "not_found");
  EXPECT_EQ(error["message"].get<std::string>().find(daemon_root()), std::string::npos)
      << "the server's own path must not leak";
}

TEST_F(ErrorsTest, PathTraversalAttemptsAreRefused) {
  for (const std::string path :
       {"../secret.glb", "BoxTextured-glTF/../../secret.glb", "/etc/passwd", "escape.glb",
        "escape_dir/BoxTextured-glTF-Binary/BoxTextured.glb"}) {
    SCOPED_TRACE(path);
    const auto result = postJson(*http, "/v1/render", withAsset(path));
    ASSERT_TRUE(result);
    EXPECT_EQ(result->status, 400) << result->body;
    EXPECT_EQ(errorOf(result).value("code", ""), "bad_request");
  }
  const auto nul =
      http->Post("/v1/render", R"({"scene": {"asset": "a\u0000.glb"}})", "application/json");
  expectError(nul, 400, "bad_request");
}

TEST_F(ErrorsTest, BrokenAssimpModelsAreClientErrors) {
  const std::vector<std::vector<std::string>> uploads = {
      {"IncorrectVertexArrays/Cube.gltf", "IncorrectVertexArrays/Cube.bin"},
      {"IndexOutOfRange/IndexOutOfRange.gltf", "IndexOutOfRange/IndexOutOfRange.bin"},
      {"IndexOutOfRange/AllIndicesOutOfRange.gltf", "IndexOutOfRange/AllIndicesOutOfRange.bin"},
      {"MissingBin/BoxTextured.gltf"},
      {"RecursiveNodes/RecursiveNodes.gltf"},
      {"SchemaFailures/sceneWrongType.gltf", "SchemaFailures/CesiumLogoFlat.png"},
      {"TestNoRootNode/NoScene.gltf"},
      {"TestNoRootNode/SceneWithoutNodes.gltf"},
      {"wrongTypes/badArray.gltf", "wrongTypes/BoxTextured0.bin", "wrongTypes/CesiumLogoFlat.png"},
      {"wrongTypes/badNumber.gltf", "wrongTypes/BoxTextured0.bin"},
      {"wrongTypes/badObject.gltf", "wrongTypes/BoxTextured0.bin"},
      {"wrongTypes/badString.gltf", "wrongTypes/BoxTextured0.bin"},
      {"wrongTypes/badUint.gltf", "wrongTypes/BoxTextured0.bin"},
      {"wrongTypes/badExtension.gltf", "wrongTypes/BoxTextured0.bin"},
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb"},
  };
  for (const auto& files : uploads) {
    SCOPED_TRACE(files.front());
    httplib::MultipartFormDataItems items{
        requestPart({{"output", {{"width", 32}, {"height", 32}}}})};
    for (const std::string& file : files) items.push_back(filePart(file));
    const auto result = http->Post("/v1/render", items);
    ASSERT_TRUE(result);
    if (result->status == 200) continue;  // a repairable file: rendering it is fine too
    EXPECT_GE(result->status, 400);
    EXPECT_LT(result->status, 500) << result->body;
    errorOf(result);
    EXPECT_EQ(http->Get("/healthz")->status, 200);
  }
}

TEST_F(ErrorsTest, UploadShapeErrorsAre400) {
  httplib::MultipartFormDataItems twoModels{filePart("BoxTextured-glTF-Binary/BoxTextured.glb"),
                                            filePart("BoxTextured-glTF/BoxTextured.gltf")};
  expectError(http->Post("/v1/render", twoModels), 400, "bad_request");
  httplib::MultipartFormDataItems sceneAndFile{requestPart({{"scene", {{"demo", true}}}}),
                                               filePart("BoxTextured-glTF-Binary/BoxTextured.glb")};
  EXPECT_EQ(expectError(http->Post("/v1/render", sceneAndFile), 400, "bad_request")["field"],
            "/scene");
  httplib::MultipartFormDataItems badJson{{"request", "{oops", "", "application/json"}};
  expectError(http->Post("/v1/render", badJson), 400, "bad_request");
}

TEST_F(ErrorsTest, UnknownRouteIs404Json) {
  expectError(http->Get("/v2/nothing"), 404, "not_found");
  // A known route with another method is 405 (test_http_conventions.cpp).
  const auto wrongMethod = http->Get("/v1/render");
  expectError(wrongMethod, 405, "method_not_allowed");
  EXPECT_EQ(wrongMethod->get_header_value("Allow"), "POST, OPTIONS");
}

TEST_F(ErrorsTest, MalformedDeadlineHeaderIs400) {
  const auto result =
      postJson(*http, "/v1/render", json::object(), {{"X-Lgh-Deadline-Ms", "soon"}});
  EXPECT_EQ(expectError(result, 400, "bad_request")["field"], "X-Lgh-Deadline-Ms");
}

class SlowRenderTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    daemon = new DaemonProcess({"--test-render-delay-ms", "600", "--queue-depth", "4"});
  }
  static void TearDownTestSuite() {
    delete daemon;
    daemon = nullptr;
  }
  void TearDown() override {
    if (HasFailure()) std::cerr << "--- lghd log ---\n" << daemon->log();
  }
  static DaemonProcess* daemon;
};
DaemonProcess* SlowRenderTest::daemon = nullptr;

TEST_F(SlowRenderTest, RenderPastItsDeadlineIs504AndTheNextOneWorks) {
  auto http = daemon->client();
  const json request = {{"output", {{"width", 32}, {"height", 32}}}};
  const auto start = std::chrono::steady_clock::now();
  const auto late = postJson(*http, "/v1/render", request, {{"X-Lgh-Deadline-Ms", "150"}});
  const auto waited = std::chrono::steady_clock::now() - start;
  expectError(late, 504, "timeout");
  EXPECT_LT(waited, std::chrono::milliseconds(550)) << "answered at the deadline, not after";

  const auto next = postJson(*http, "/v1/render", request);
  ASSERT_TRUE(next);
  ASSERT_EQ(next->status, 200) << next->body;
  EXPECT_EQ(decodeBody(next->body).width, 32);
  const std::string metrics = http->Get("/metrics")->body;
  EXPECT_EQ(metricValue(metrics, "lghd_renders_total{outcome=\"timeout\"}"), 1);
}

TEST_F(SlowRenderTest, JobWhoseDeadlinePassesInTheQueueIsNotRendered) {
  auto first = daemon->client();
  auto second = daemon->client();
  const json request = {{"output", {{"width", 32}, {"height", 32}}}};
  const double skippedBefore =
      metricValue(first->Get("/metrics")->body, "lghd_renders_total{outcome=\"skipped\"}");
  std::thread slow([&] { EXPECT_EQ(postJson(*first, "/v1/render", request)->status, 200); });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto expired = postJson(*second, "/v1/render", request, {{"X-Lgh-Deadline-Ms", "200"}});
  slow.join();
  const json error = expectError(expired, 504, "timeout");
  EXPECT_NE(error["message"].get<std::string>().find("queue"), std::string::npos);
  // The render thread skips it when it gets there.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(metricValue(first->Get("/metrics")->body, "lghd_renders_total{outcome=\"skipped\"}"),
            skippedBefore + 1);
}

TEST(AuthTest, BearerTokenGuardsEverythingButTheProbes) {
  DaemonProcess daemon({}, {"LGHD_AUTH_TOKEN=s3cret"});
  auto http = daemon.client();
  const json error = expectError(http->Get("/v1/info"), 401, "unauthorized");
  EXPECT_EQ(http->Get("/healthz")->status, 200);
  EXPECT_EQ(http->Get("/readyz")->status, 200);
  http->set_bearer_token_auth("wrong");
  expectError(http->Get("/v1/info"), 401, "unauthorized");
  http->set_bearer_token_auth("s3cret");
  EXPECT_EQ(http->Get("/v1/info")->status, 200);
  EXPECT_EQ(postJson(*http, "/v1/render", {{"output", {{"width", 16}, {"height", 16}}}})->status,
            200);
}

TEST(ConfigTest, FlagsWinOverEnvironmentVariables) {
  DaemonProcess daemon({"--max-width", "200"}, {"LGHD_MAX_WIDTH=100", "LGHD_MAX_HEIGHT=50"});
  auto http = daemon.client();
  const json limits = json::parse(http->Get("/v1/info")->body)["limits"];
  EXPECT_EQ(limits["max_width"], 200);
  EXPECT_EQ(limits["max_height"], 50);
  EXPECT_EQ(postJson(*http, "/v1/render", {{"output", {{"width", 150}, {"height", 40}}}})->status,
            200);
}

TEST(VulkanProbeTest, NoVulkanDriverIsReportedAndRenderingGoesOn) {
  // The loader finds no driver: /v1/info says why, GL rendering is untouched, shutdown is clean.
  DaemonProcess daemon(
      {}, {"VK_DRIVER_FILES=/nonexistent/icd.json", "VK_ICD_FILENAMES=/nonexistent/icd.json"});
  auto http = daemon.client();
  json vulkan;
  for (int i = 0; i < 100; ++i) {
    vulkan = json::parse(http->Get("/v1/info")->body).at("vulkan");
    if (!vulkan.at("available").is_null()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_EQ(vulkan.at("available"), false) << vulkan.dump();
  EXPECT_FALSE(vulkan.value("error", "").empty()) << vulkan.dump();
  EXPECT_EQ(postJson(*http, "/v1/render", {{"output", {{"width", 16}, {"height", 16}}}})->status,
            200);
  EXPECT_EQ(daemon.stop(SIGTERM, std::chrono::seconds(20)), 0) << daemon.log();
}

TEST(ConfigTest, HelpNamesFlagsAndVariables) {
  const auto [status, output] = runLghd({"--help"});
  EXPECT_EQ(status, 0);
  for (const char* text : {"--port", "LGHD_PORT", "--asset-root", "LGHD_ASSET_ROOT", "--gpu",
                           "--max-body-mb", "--queue-depth", "--grace-seconds", "/v1/render"}) {
    EXPECT_NE(output.find(text), std::string::npos) << text << " missing from:\n" << output;
  }
  EXPECT_EQ(runLghd({"--port", "nope"}).first, 2);
}

}  // namespace
}  // namespace lghd::test
