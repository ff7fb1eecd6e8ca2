// Happy paths of the real daemon on loopback: PNG, EXR and JSON renders, asset paths and
// uploads, the scene cache, metrics, info, health and the OpenAPI document.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "daemon_process.hpp"
#include "http_helpers.hpp"

namespace lghd::test {
namespace {

class RenderTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { daemon = new DaemonProcess({"--max-pixels", "1048576"}); }
  static void TearDownTestSuite() {
    delete daemon;
    daemon = nullptr;
  }
  void SetUp() override { http = daemon->client(); }
  void TearDown() override {
    if (HasFailure()) std::cerr << "--- lghd log ---\n" << daemon->log();
  }

  static DaemonProcess* daemon;
  std::unique_ptr<httplib::Client> http;
};
DaemonProcess* RenderTest::daemon = nullptr;

json smallRequest(int width, int height, const std::string& format = "png") {
  return {{"output", {{"width", width}, {"height", height}, {"format", format}}}};
}

TEST_F(RenderTest, PngDecodesToRequestedSize) {
  const auto result = postJson(*http, "/v1/render", smallRequest(96, 64));
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  EXPECT_EQ(result->get_header_value("Content-Type"), "image/png");
  const auto image = decodeBody(result->body);
  EXPECT_EQ(image.width, 96);
  EXPECT_EQ(image.height, 64);
  EXPECT_FALSE(image.isFloat);

  const json timings = json::parse(result->get_header_value("X-Lgh-Timings"));
  ASSERT_TRUE(timings.is_array());
  EXPECT_FALSE(timings.empty());
  for (const json& row : timings) {
    EXPECT_TRUE(row.contains("pass") && row.contains("clock") && row.contains("ms")) << row;
  }
  EXPECT_FALSE(result->get_header_value("X-Lgh-Renderer").empty());
  EXPECT_FALSE(result->get_header_value("X-Request-Id").empty());
  EXPECT_FALSE(result->get_header_value("Server-Timing").empty());
  const std::string cache = result->get_header_value("X-Lgh-Cache");
  EXPECT_TRUE(cache == "hit" || cache == "miss") << cache;
}

// The lecture's models and techniques through the daemon: per-request material parameters over
// the demo's materials, applied to that frame only: the cached demo renders as before afterwards.
TEST_F(RenderTest, MaterialParametersApplyToTheirRenderOnly) {
  const json plain = smallRequest(64, 48);
  json styled = plain;
  styled["materials"] = {
      {{"match", {{"name", "floor_checker"}}},
       {"parameters",
        {{"surface", "relief"}, {"height_texture", {{"texture", 1}}}, {"height_scale", 0.05}}}},
      {{"match", {{"name", "white"}}},
       {"parameters", {{"model", "blinn-phong"}, {"shading", "gouraud"}, {"shininess", 60}}}},
      {{"match", {{"name", "metal"}}}, {"parameters", {{"alpha_mode", "blend"}, {"alpha", 0.4}}}}};
  const auto before = postJson(*http, "/v1/render", plain);
  const auto changed = postJson(*http, "/v1/render", styled, {{"Accept", "application/json"}});
  const auto after = postJson(*http, "/v1/render", plain);
  ASSERT_TRUE(before && changed && after);
  ASSERT_EQ(changed->status, 200) << changed->body;
  const json answer = json::parse(changed->body);
  EXPECT_EQ(answer["paths"]["blended_surfaces"], "1");
  EXPECT_NE(answer["paths"]["texture_memory"].get<std::string>().find("MiB"), std::string::npos);
  EXPECT_GE(std::stof(answer["paths"]["texture_anisotropy"].get<std::string>()), 1.0F);
  EXPECT_EQ(changed->get_header_value("X-Lgh-Cache"), "hit") << "the overrides are not a scene";
  ASSERT_EQ(before->status, 200);
  ASSERT_EQ(after->status, 200);
  EXPECT_EQ(decodeBody(before->body).pixels8, decodeBody(after->body).pixels8)
      << "the cached demo kept its own materials";
}

TEST_F(RenderTest, ExrDecodesToRequestedSize) {
  const auto result = postJson(*http, "/v1/render", smallRequest(48, 32, "exr-float"));
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  EXPECT_EQ(result->get_header_value("Content-Type"), "image/x-exr");
  const auto image = decodeBody(result->body);
  EXPECT_EQ(image.width, 48);
  EXPECT_EQ(image.height, 32);
  EXPECT_TRUE(image.isFloat);
}

TEST_F(RenderTest, EmptyObjectRendersTheDemo) {
  const auto result = http->Post("/v1/render", "{}", "application/json");
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  const auto image = decodeBody(result->body);
  EXPECT_EQ(image.width, 640);
  EXPECT_EQ(image.height, 360);
}

TEST_F(RenderTest, JsonModeHoldsImageTimingsDeviceAndRequestId) {
  const auto result = postJson(*http, "/v1/render", smallRequest(40, 30),
                               {{"Accept", "application/json"}, {"X-Request-Id", "json-mode-1"}});
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  EXPECT_EQ(result->get_header_value("Content-Type"), "application/json");
  const json body = json::parse(result->body);
  for (const char* key : {"image", "mime", "width", "height", "timings", "device", "paths",
                          "warnings", "request_id"}) {
    EXPECT_TRUE(body.contains(key)) << key;
  }
  EXPECT_EQ(body["mime"], "image/png");
  EXPECT_EQ(body["width"], 40);
  EXPECT_EQ(body["request_id"], "json-mode-1");
  EXPECT_EQ(result->get_header_value("X-Request-Id"), "json-mode-1");
  EXPECT_FALSE(body["device"].value("gl_renderer", "").empty());
  const std::string& encoded = body["image"].get_ref<const std::string&>();
  EXPECT_EQ(encoded.size() % 4, 0U);
  EXPECT_EQ(encoded.rfind("iVBORw0KGgo", 0), 0U) << "base64 of a PNG starts with iVBORw0KGgo";
}

TEST_F(RenderTest, AssetPathInTheRootRenders) {
  json request = smallRequest(64, 64);
  request["scene"] = {{"asset", "BoxTextured-glTF/BoxTextured.gltf"}};
  const auto result = postJson(*http, "/v1/render", request);
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  EXPECT_EQ(decodeBody(result->body).width, 64);
}

TEST_F(RenderTest, UploadedGlbRenders) {
  const auto result = http->Post(
      "/v1/render",
      httplib::MultipartFormDataItems{requestPart(smallRequest(64, 48)),
                                      filePart("BoxTextured-glTF-Binary/BoxTextured.glb")});
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  const auto image = decodeBody(result->body);
  EXPECT_EQ(image.width, 64);
  EXPECT_EQ(image.height, 48);
}

TEST_F(RenderTest, UploadedGltfWithSideFilesRenders) {
  const auto result =
      http->Post("/v1/render",
                 httplib::MultipartFormDataItems{requestPart(smallRequest(64, 64)),
                                                 filePart("BoxTextured-glTF/BoxTextured.gltf"),
                                                 filePart("BoxTextured-glTF/BoxTextured0.bin"),
                                                 filePart("BoxTextured-glTF/CesiumLogoFlat.png")});
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  EXPECT_EQ(decodeBody(result->body).width, 64);
}

TEST_F(RenderTest, CacheHitIsFasterThanTheMissAndRecorded) {
  const double hitsBefore = metricValue(http->Get("/metrics")->body, "lghd_scene_cache_hits_total");
  json request = smallRequest(32, 32);
  request["scene"] = {{"asset", "2CylinderEngine-glTF-Binary/2CylinderEngine.glb"}};
  const auto miss = postJson(*http, "/v1/render", request);
  const auto hit = postJson(*http, "/v1/render", request);
  ASSERT_TRUE(miss && hit);
  ASSERT_EQ(miss->status, 200) << miss->body;
  ASSERT_EQ(hit->status, 200) << hit->body;
  EXPECT_EQ(miss->get_header_value("X-Lgh-Cache"), "miss");
  EXPECT_EQ(hit->get_header_value("X-Lgh-Cache"), "hit");
  EXPECT_EQ(json::parse(hit->get_header_value("X-Lgh-Paths")).value("scene_cache", ""), "hit");
  const double missMs = std::stod(miss->get_header_value("X-Lgh-Render-Ms"));
  const double hitMs = std::stod(hit->get_header_value("X-Lgh-Render-Ms"));
  EXPECT_LT(hitMs, missMs);
  const std::string metrics = http->Get("/metrics")->body;
  EXPECT_GE(metricValue(metrics, "lghd_scene_cache_hits_total"), hitsBefore + 1);
  EXPECT_GE(metricValue(metrics, "lghd_render_duration_seconds_count{scene_cache=\"hit\"}"), 1);
}

TEST_F(RenderTest, MetricsCountersMove) {
  const std::string series =
      "lghd_http_requests_total{route=\"/v1/render\",method=\"POST\",status=\"200\"}";
  const double before = metricValue(http->Get("/metrics")->body, series);
  ASSERT_EQ(postJson(*http, "/v1/render", smallRequest(32, 32))->status, 200);
  EXPECT_GE(waitForMetric(*http, series, before + 1), before + 1);
  const auto metrics = http->Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_EQ(metrics->status, 200);
  EXPECT_NE(metrics->get_header_value("Content-Type").find("text/plain"), std::string::npos);
  const std::string& text = metrics->body;
  EXPECT_GE(metricValue(text, "lghd_http_request_duration_seconds_count{route=\"/v1/render\"}"),
            before + 1);
  EXPECT_GE(metricValue(text, "lghd_renders_total{outcome=\"ok\"}"), 1);
  EXPECT_EQ(metricValue(text, "lghd_ready"), 1);
  EXPECT_EQ(metricValue(text, "lghd_queue_capacity"), 16);
  EXPECT_NE(text.find("lghd_render_pass_seconds_bucket{pass="), std::string::npos);
  EXPECT_NE(text.find("lghd_queue_depth "), std::string::npos);
}

TEST_F(RenderTest, InfoHealthAndReady) {
  const auto info = http->Get("/v1/info");
  ASSERT_TRUE(info);
  ASSERT_EQ(info->status, 200);
  const json body = json::parse(info->body);
  EXPECT_TRUE(body["ready"].get<bool>());
  EXPECT_FALSE(body["device"].value("gl_version", "").empty());
  EXPECT_EQ(body["limits"]["max_pixels"], 1048576);
  EXPECT_EQ(body["limits"]["max_width"], 4096);
  // The test machines have Mesa's lavapipe: the probe (on its own thread, so possibly still
  // running at "ready") must find it and say what it offers.
  json vulkan = body.at("vulkan");
  for (int i = 0; i < 100 && vulkan.at("available").is_null(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    vulkan = json::parse(http->Get("/v1/info")->body).at("vulkan");
  }
  EXPECT_TRUE(vulkan.at("available").get<bool>()) << vulkan.dump();
  EXPECT_FALSE(vulkan.at("loader_version").get<std::string>().empty());
  ASSERT_FALSE(vulkan.at("devices").empty()) << vulkan.dump();
  EXPECT_FALSE(vulkan["devices"][0].at("name").get<std::string>().empty());
  EXPECT_TRUE(vulkan["devices"][0].at("ray_query").is_boolean());
  // The shadow tracer of the GL device: made by the start-up self-test render (shadows "auto").
  const json shadows = body.at("shadows");
  EXPECT_EQ(shadows.at("status"), "ready") << shadows.dump();
  EXPECT_EQ(shadows.at("process"), "in-process");
  EXPECT_FALSE(shadows.at("device").get<std::string>().empty());
  EXPECT_EQ(shadows.at("transport"), "pinned") << "llvmpipe pins lavapipe's memory, not imports it";
  EXPECT_TRUE(body["build"].contains("version"));
  EXPECT_EQ(http->Get("/healthz")->status, 200);
  EXPECT_EQ(http->Get("/readyz")->status, 200);
}

TEST_F(RenderTest, OpenApiAndItsSchemasAreServed) {
  const auto document = http->Get("/openapi.json");
  ASSERT_TRUE(document);
  ASSERT_EQ(document->status, 200);
  const json openapi = json::parse(document->body);
  EXPECT_EQ(openapi["openapi"].get<std::string>().substr(0, 2), "3.");
  for (const char* path : {"/v1/render", "/v1/thumbnails", "/v1/info", "/healthz", "/readyz",
                           "/metrics", "/openapi.json", "/v1/benchmark", "/v1/benchmark/result"}) {
    EXPECT_TRUE(openapi["paths"].contains(path)) << path;
  }
  const auto schema = http->Get("/render-request.schema.json");
  ASSERT_TRUE(schema);
  EXPECT_EQ(schema->status, 200);
  EXPECT_EQ(json::parse(schema->body)["title"], "lghd render request");
  EXPECT_EQ(http->Get("/proto/camera.schema.json")->status, 200);
}

}  // namespace
}  // namespace lghd::test
