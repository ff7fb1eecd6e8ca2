// POST /v1/thumbnails against the real daemon: ZIP and NDJSON answers, uploads, views and name
// templates, and bad assets that must not sink the batch.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "daemon_process.hpp"
#include "http_helpers.hpp"
#include "lgh/base64.hpp"

namespace lghd::test {
namespace {

class ThumbnailsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { daemon = new DaemonProcess({"--max-batch", "8"}); }
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
DaemonProcess* ThumbnailsTest::daemon = nullptr;

std::vector<json> ndjsonLines(const std::string& body) {
  std::vector<json> lines;
  std::istringstream stream(body);
  std::string line;
  while (std::getline(stream, line)) {
    if (!line.empty()) lines.push_back(json::parse(line));
  }
  return lines;
}

TEST_F(ThumbnailsTest, ZipHoldsGoodThumbnailsAndErrorsOfBadAssets) {
  const json request = {{"assets",
                         {"BoxTextured-glTF-Binary/BoxTextured.glb", "missing/Nothing.glb",
                          "BoxTextured-glTF/BoxTextured.gltf", "../secret.glb"}},
                        {"width", 64},
                        {"height", 48},
                        {"name_template", "{index}-{name}_{view}.png"}};
  const auto result = postJson(*http, "/v1/thumbnails", request);
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  EXPECT_EQ(result->get_header_value("Content-Type"), "application/zip");
  EXPECT_EQ(result->get_header_value("X-Lgh-Thumbnails-Ok"), "2");
  EXPECT_EQ(result->get_header_value("X-Lgh-Thumbnails-Failed"), "2");
  const auto members = unzip(result->body);
  ASSERT_EQ(members.size(), 3U);
  ASSERT_TRUE(members.contains("0-BoxTextured_default.png"));
  ASSERT_TRUE(members.contains("2-BoxTextured_default.png"));
  const auto image = decodeBody(members.at("0-BoxTextured_default.png"));
  EXPECT_EQ(image.width, 64);
  EXPECT_EQ(image.height, 48);

  ASSERT_TRUE(members.contains("errors.json"));
  const json errors = json::parse(members.at("errors.json"));
  ASSERT_EQ(errors.size(), 2U);
  EXPECT_EQ(errors[0]["asset"], "missing/Nothing.glb");
  EXPECT_EQ(errors[0]["error"]["code"], "not_found");
  EXPECT_EQ(errors[0]["error"]["field"], "/assets/1");
  EXPECT_EQ(errors[1]["asset"], "../secret.glb");
  EXPECT_EQ(errors[1]["error"]["code"], "bad_request");
}

TEST_F(ThumbnailsTest, NdjsonStreamsEachResultWithProgressThenASummary) {
  const json request = {{"assets",
                         {"BoxTextured-glTF-Binary/BoxTextured.glb", "escape.glb",
                          "BoxTextured-glTF-Embedded/BoxTextured.gltf"}},
                        {"width", 32},
                        {"height", 32},
                        {"format", "ndjson"},
                        {"transparent_background", true}};
  httplib::Request streamed;
  streamed.method = "POST";
  streamed.path = "/v1/thumbnails";
  streamed.body = request.dump();
  streamed.set_header("Content-Type", "application/json");
  std::string body;
  int chunks = 0;
  streamed.content_receiver = [&](const char* data, std::size_t length, std::uint64_t,
                                  std::uint64_t) {
    body.append(data, length);
    ++chunks;
    return true;
  };
  httplib::Response response;
  httplib::Error error = httplib::Error::Success;
  ASSERT_TRUE(http->send(streamed, response, error)) << httplib::to_string(error);
  ASSERT_EQ(response.status, 200);
  EXPECT_EQ(response.get_header_value("Content-Type"), "application/x-ndjson");
  EXPECT_GE(chunks, 2) << "each result should arrive as it finishes";

  const std::vector<json> lines = ndjsonLines(body);
  ASSERT_EQ(lines.size(), 4U) << body;
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(lines[i]["index"], i);
    EXPECT_EQ(lines[i]["total"], 3);
    EXPECT_EQ(lines[i]["completed"], i + 1);
  }
  EXPECT_EQ(lines[0]["status"], "ok");
  EXPECT_EQ(lines[1]["status"], "error");
  EXPECT_EQ(lines[1]["error"]["code"], "bad_request");
  EXPECT_EQ(lines[2]["status"], "ok");
  EXPECT_TRUE(lines[0]["timings"].is_array());

  const std::string png = lines[0]["image_base64"];
  EXPECT_EQ(png.rfind("iVBORw0KGgo", 0), 0U);
  EXPECT_EQ(lines[3]["status"], "done");
  EXPECT_EQ(lines[3]["ok"], 2);
  EXPECT_EQ(lines[3]["failed"], 1);
}

TEST_F(ThumbnailsTest, TransparentBackgroundLeavesAlphaZeroAroundTheModel) {
  const json request = {{"assets", {"BoxTextured-glTF-Binary/BoxTextured.glb"}},
                        {"width", 64},
                        {"height", 64},
                        {"transparent_background", true}};
  const auto result = postJson(*http, "/v1/thumbnails", request);
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  const auto members = unzip(result->body);
  ASSERT_EQ(members.size(), 1U);
  const auto image = decodeBody(members.begin()->second);
  ASSERT_EQ(image.channels, 4);
  EXPECT_EQ(image.pixels8[3], 0) << "the corner pixel is background";
  const std::size_t centre = (32 * 64 + 32) * 4 + 3;
  EXPECT_EQ(image.pixels8[centre], 255) << "the centre pixel is the box";
}

TEST_F(ThumbnailsTest, PngCompressionChangesTheSizeNotThePixels) {
  std::vector<std::string> pngs;
  for (const int level : {0, 9}) {
    const json request = {{"assets", {"BoxTextured-glTF-Binary/BoxTextured.glb"}},
                          {"width", 64},
                          {"height", 64},
                          {"png_compression", level}};
    const auto result = postJson(*http, "/v1/thumbnails", request);
    ASSERT_TRUE(result);
    ASSERT_EQ(result->status, 200) << result->body;
    const auto members = unzip(result->body);
    ASSERT_EQ(members.size(), 1U);
    pngs.push_back(members.begin()->second);
  }
  EXPECT_GT(pngs[0].size(), 64U * 64U * 3U) << "level 0 stores the rows";
  EXPECT_LT(pngs[1].size(), pngs[0].size());
  EXPECT_EQ(decodeBody(pngs[0]).pixels8, decodeBody(pngs[1]).pixels8);
}

TEST_F(ThumbnailsTest, UploadsAndSeveralViewsWithANameTemplate) {
  const json options = {{"width", 32},
                        {"height", 32},
                        {"views",
                         {{{"name", "front"}, {"direction", {0, 0, 1}}},
                          {{"name", "top"}, {"direction", {0, 1, 0.01}}}}},
                        {"name_template", "{name}-{view}.png"}};
  const auto result = http->Post(
      "/v1/thumbnails",
      httplib::MultipartFormDataItems{requestPart(options),
                                      filePart("BoxTextured-glTF-Binary/BoxTextured.glb", "a.glb"),
                                      filePart("BoxTextured-glTF/BoxTextured.gltf"),
                                      filePart("BoxTextured-glTF/BoxTextured0.bin"),
                                      filePart("BoxTextured-glTF/CesiumLogoFlat.png")});
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  const auto members = unzip(result->body);
  std::set<std::string> names;
  for (const auto& [name, bytes] : members) names.insert(name);
  EXPECT_EQ(names, (std::set<std::string>{"a-front.png", "a-top.png", "BoxTextured-front.png",
                                          "BoxTextured-top.png"}));
}

TEST_F(ThumbnailsTest, DuplicateNamesAreMadeUnique) {
  const json request = {
      {"assets",
       {"BoxTextured-glTF-Binary/BoxTextured.glb", "BoxTextured-glTF-Binary/BoxTextured.glb"}},
      {"width", 32},
      {"height", 32}};
  const auto result = postJson(*http, "/v1/thumbnails", request);
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  EXPECT_EQ(unzip(result->body).size(), 2U);
}

TEST_F(ThumbnailsTest, BatchLevelErrors) {
  expectError(postJson(*http, "/v1/thumbnails", json::object()), 400, "bad_request");
  const json tooMany = {{"assets", std::vector<std::string>(9, "a.glb")}};
  EXPECT_EQ(expectError(postJson(*http, "/v1/thumbnails", tooMany), 413, "too_large")["field"],
            "/assets");
  const json wide = {{"assets", {"a.glb"}}, {"width", 5000}};
  EXPECT_EQ(expectError(postJson(*http, "/v1/thumbnails", wide), 413, "too_large")["field"],
            "/width");
  const json badTemplate = {{"assets", {"a.glb"}}, {"name_template", "{nope}.png"}};
  EXPECT_EQ(
      expectError(postJson(*http, "/v1/thumbnails", badTemplate), 400, "bad_request")["field"],
      "/name_template");
  const json zeroView = {{"assets", {"a.glb"}}, {"view_direction", {0, 0, 0}}};
  EXPECT_EQ(expectError(postJson(*http, "/v1/thumbnails", zeroView), 422, "invalid")["field"],
            "/view_direction");
  const json badLevel = {{"assets", {"a.glb"}}, {"png_compression", 12}};
  EXPECT_EQ(expectError(postJson(*http, "/v1/thumbnails", badLevel), 422, "invalid")["field"],
            "/png_compression");
  const json unknown = {{"assets", {"a.glb"}}, {"colour", "red"}};
  expectError(postJson(*http, "/v1/thumbnails", unknown), 400, "bad_request");
  EXPECT_EQ(http->Get("/healthz")->status, 200);
}

// With several scene parser processes the assets a batch draws next parse side by side: more than
// one parser starts, a broken asset still fails only its own thumbnail, and every image equals
// what one parser gives.
TEST(ThumbnailsSceneParsers, ABatchParsesOnSeveralProcessesAndMatchesOneParser) {
  const json request = {
      {"assets",
       {"BoxTextured-glTF-Binary/BoxTextured.glb",
        "2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "BoxTextured-glTF/BoxTextured.gltf",
        "IndexOutOfRange/IndexOutOfRange.gltf", "BoxTexcoords-glTF/boxTexcoords.gltf",
        "BoxTextured-glTF-Embedded/BoxTextured.gltf"}},
      {"width", 32},
      {"height", 32},
      {"name_template", "{index}.png"}};
  std::map<std::string, std::string> images[2];
  for (const int parsers : {3, 1}) {
    const DaemonProcess daemon(
        {"--scene-parsers", std::to_string(parsers), "--scene-cache-mb", "0"});
    auto http = daemon.client(std::chrono::seconds(120));
    const auto result = postJson(*http, "/v1/thumbnails", request);
    ASSERT_TRUE(result);
    ASSERT_EQ(result->status, 200) << result->body.substr(0, 300);
    EXPECT_EQ(result->get_header_value("X-Lgh-Thumbnails-Failed"), "1") << "IndexOutOfRange";
    images[parsers == 3 ? 0 : 1] = unzip(result->body);
    const std::string log = daemon.log();
    EXPECT_NE(log.find(fmt::format("\"scene_parsers\":{}", parsers)), std::string::npos);
    std::size_t started = 0;
    for (std::size_t at = log.find("scene worker: pid"); at != std::string::npos;
         at = log.find("scene worker: pid", at + 1)) {
      ++started;
    }
    if (parsers == 3) {
      EXPECT_GE(started, 2U) << log;
      EXPECT_LE(started, 3U) << log;
    } else {
      EXPECT_EQ(started, 1U) << log;
    }
  }
  ASSERT_EQ(images[0].size(), 6U) << "five thumbnails and errors.json";
  ASSERT_EQ(images[1].size(), images[0].size());
  for (const auto& [name, bytes] : images[0]) {
    if (name == "errors.json") continue;
    ASSERT_TRUE(images[1].contains(name)) << name;
    EXPECT_EQ(decodeBody(bytes, name).pixels8, decodeBody(images[1].at(name), name).pixels8)
        << name;
  }
}

// A batch whose first asset takes far longer to parse and to build acceleration structures for
// than the rest (2CylinderEngine against boxes): with two parser processes the boxes are at hand
// while the engine is still on its way, and the render thread draws them first. The answer keeps
// the request's order, and every image has the pixels of the one drawn with one parser.
std::vector<std::uint8_t> pixelsOf(const json& line) {
  const auto bytes = lgh::base64::decode(line.at("image_base64").get<std::string>());
  const auto& png = std::get<std::vector<std::uint8_t>>(bytes);
  return decodeBody(std::string(png.begin(), png.end()), line.at("file")).pixels8;
}

// Drawing ahead depends on timing: a render thread that first looks once every scene is ready
// (held up on a loaded machine) draws in order. The batch posted again, up to `tries` times in
// all, gives it more chances; the daemon's counter of items drawn ahead after them.
constexpr int kDrawAheadTries = 3;
double drawnAheadWithin(httplib::Client& http, const json& request, int tries) {
  double drawnAhead = metricValue(http.Get("/metrics")->body, "lghd_renders_drawn_ahead_total");
  for (int again = 1; again < tries && drawnAhead < 1.0; ++again) {
    const auto result = postJson(http, "/v1/thumbnails", request);
    if (!result || result->status != 200) break;
    drawnAhead = metricValue(http.Get("/metrics")->body, "lghd_renders_drawn_ahead_total");
  }
  return drawnAhead;
}

TEST(ThumbnailsSceneParsers, ReadyScenesAreDrawnAheadOfASlowOneAndAnswersKeepTheirOrder) {
  json assets = json::array({"2CylinderEngine-glTF-Binary/2CylinderEngine.glb"});
  for (int i = 0; i < 3; ++i) {
    assets.push_back("BoxTextured-glTF-Binary/BoxTextured.glb");
    assets.push_back("BoxTexcoords-glTF/boxTexcoords.gltf");
  }
  const json request = {{"assets", assets},
                        {"width", 32},
                        {"height", 32},
                        {"format", "ndjson"},
                        {"name_template", "{index}.png"}};
  std::vector<json> lines[2];
  double drawnAhead = 0.0;
  for (const int parsers : {2, 1}) {
    const DaemonProcess daemon(
        {"--scene-parsers", std::to_string(parsers), "--scene-cache-mb", "0"});
    auto http = daemon.client(std::chrono::seconds(120));
    const auto result = postJson(*http, "/v1/thumbnails", request);
    ASSERT_TRUE(result);
    ASSERT_EQ(result->status, 200) << result->body.substr(0, 300);
    std::vector<json>& mine = lines[parsers == 2 ? 0 : 1];
    for (const json& line : ndjsonLines(result->body)) {
      if (line.contains("index")) mine.push_back(line);
    }
    if (parsers == 2) drawnAhead = drawnAheadWithin(*http, request, kDrawAheadTries);
  }
  EXPECT_GE(drawnAhead, 1.0) << "the boxes were at hand while the engine was on its way";
  ASSERT_EQ(lines[0].size(), assets.size());
  ASSERT_EQ(lines[1].size(), assets.size());
  for (std::size_t i = 0; i < assets.size(); ++i) {
    EXPECT_EQ(lines[0][i].at("index"), i) << "NDJSON lines in the request's order";
    EXPECT_EQ(lines[0][i].at("asset"), assets[i]);
    ASSERT_EQ(lines[0][i].at("status"), "ok") << lines[0][i].dump().substr(0, 300);
    ASSERT_EQ(lines[1][i].at("status"), "ok") << lines[1][i].dump().substr(0, 300);
    EXPECT_EQ(pixelsOf(lines[0][i]), pixelsOf(lines[1][i])) << "thumbnail " << i;
  }
}

// With one parser process, a batch of distinct files that begins with a large one: its start is
// hinted smallest file first, so that the parser does the boxes before the engine and the render
// thread draws them while the engine parses, rather than waiting for the engine first. The answer
// keeps the request's order.
TEST(ThumbnailsSceneParsers, ABatchStartsWithItsSmallestFilesAndAnswersKeepTheirOrder) {
  const json assets = json::array(
      {"2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "BoxTextured-glTF-Binary/BoxTextured.glb",
       "BoxTexcoords-glTF/boxTexcoords.gltf", "BoxBadNormals-glTF-Binary/BoxBadNormals.glb"});
  const json request = {{"assets", assets},
                        {"width", 32},
                        {"height", 32},
                        {"format", "ndjson"},
                        {"name_template", "{index}.png"}};
  const DaemonProcess daemon({"--scene-parsers", "1", "--scene-cache-mb", "0"});
  auto http = daemon.client(std::chrono::seconds(120));
  const auto result = postJson(*http, "/v1/thumbnails", request);
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body.substr(0, 300);
  std::vector<json> lines;
  for (const json& line : ndjsonLines(result->body)) {
    if (line.contains("index")) lines.push_back(line);
  }
  ASSERT_EQ(lines.size(), assets.size());
  for (std::size_t i = 0; i < assets.size(); ++i) {
    EXPECT_EQ(lines[i].at("index"), i) << "NDJSON lines in the request's order";
    EXPECT_EQ(lines[i].at("asset"), assets[i]);
    EXPECT_EQ(lines[i].at("status"), "ok") << lines[i].dump().substr(0, 300);
  }
  EXPECT_GE(drawnAheadWithin(*http, request, kDrawAheadTries), 1.0)
      << "a box was drawn while the engine was still being parsed";
}

}  // namespace
}  // namespace lghd::test
