// Hostile input against the real lghd: raw HTTP framing attacks spoken byte by byte over a socket
// (RFC 9112 6.3: conflicting lengths, Content-Length with Transfer-Encoding, bad chunks, folded
// and oversized headers, smuggled requests), every hand-made hostile glTF asset by path and by
// upload, deeply nested JSON, a scene parser worker that crashes or runs past its time, capped
// response headers and the token-free metrics port. After each, the daemon must still serve.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "daemon_process.hpp"
#include "http_helpers.hpp"

namespace lghd::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

DaemonProcess& daemon() {
  static DaemonProcess process({"--deadline-seconds", "120"});
  return process;
}

// What a raw connection got back: every byte until the server closed (or 1.5 s of silence).
struct Exchange {
  std::string bytes;
  bool closedByServer = false;

  int statusCount() const {
    int count = 0;  // status lines: at the start, or right after a previous answer's body
    for (std::size_t at = bytes.find("HTTP/1.1 "); at != std::string::npos;
         at = bytes.find("HTTP/1.1 ", at + 1)) {
      if (at == 0 || bytes[at - 1] == '\n' || bytes[at - 1] == '}') ++count;
    }
    return count;
  }
  int firstStatus() const {
    const std::size_t at = bytes.find("HTTP/1.1 ");
    return at == std::string::npos ? 0 : std::stoi(bytes.substr(at + 9, 3));
  }
};

Exchange sendRaw(int port, const std::string& request) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  Exchange exchange;
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
    ::close(fd);
    ADD_FAILURE() << "cannot connect to lghd";
    return exchange;
  }
  for (std::size_t sent = 0; sent < request.size();) {
    const ssize_t count = ::send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
    if (count <= 0) break;
    sent += static_cast<std::size_t>(count);
  }
  char buffer[65536];
  for (;;) {
    pollfd entry{fd, POLLIN, 0};
    if (::poll(&entry, 1, 1500) <= 0) break;  // silence: the connection stays open
    const ssize_t count = ::recv(fd, buffer, sizeof(buffer), 0);
    if (count <= 0) {
      exchange.closedByServer = true;
      break;
    }
    exchange.bytes.append(buffer, static_cast<std::size_t>(count));
  }
  ::close(fd);
  return exchange;
}

void expectAlive() {
  auto http = daemon().client();
  const auto health = http->Get("/healthz");
  ASSERT_TRUE(health) << "lghd stopped answering:\n" << daemon().log();
  EXPECT_EQ(health->status, 200);
  EXPECT_FALSE(daemon().exited());
}

const std::string kHealth = "GET /healthz HTTP/1.1\r\nHost: t\r\n\r\n";

// --- HTTP framing ------------------------------------------------------------------------------

struct FramingCase {
  const char* name;
  std::string request;
  int status;
  const char* field;  // the error body's "field"
};

TEST(HttpFraming, BrokenFramingIsRefusedAndTheConnectionClosed) {
  const std::string post =
      "POST /v1/render HTTP/1.1\r\nHost: t\r\nContent-Type: application/json\r\n";
  const std::vector<FramingCase> cases = {
      {"conflicting Content-Length",
       post + "Content-Length: 2\r\nContent-Length: 40\r\n\r\n{}" + kHealth, 400, "Content-Length"},
      {"duplicate Content-Length", post + "Content-Length: 2\r\nContent-Length: 2\r\n\r\n{}", 400,
       "Content-Length"},
      {"Content-Length list", post + "Content-Length: 2, 2\r\n\r\n{}", 400, "Content-Length"},
      {"signed Content-Length", post + "Content-Length: +2\r\n\r\n{}", 400, "Content-Length"},
      {"percent-encoded Content-Length", post + "Content-Length: %32\r\n\r\n{}", 400,
       "Content-Length"},
      {"Content-Length with Transfer-Encoding",
       post + "Content-Length: 5\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\n", 400,
       "Transfer-Encoding"},
      {"Transfer-Encoding not ending in chunked",
       post + "Transfer-Encoding: chunked, identity\r\n\r\n0\r\n\r\n", 400, "Transfer-Encoding"},
      {"chunked twice", post + "Transfer-Encoding: chunked\r\nTransfer-Encoding: chunked\r\n\r\n",
       400, "Transfer-Encoding"},
      {"whitespace before the colon", post + "Content-Length : 2\r\n\r\n{}", 400, "Content-Length"},
      {"obs-fold", "GET /healthz HTTP/1.1\r\nHost: t\r\nX-A: 1\r\n continued\r\n\r\n", 400, "head"},
      {"bare LF", "GET /healthz HTTP/1.1\nHost: t\n\n", 400, "head"},
      {"bare CR", "GET /healthz HTTP/1.1\r\nHost: t\rX: 1\r\n\r\n", 400, "head"},
      {"NUL in a value", std::string("GET /healthz HTTP/1.1\r\nHost: t\r\nX-A: a\0b\r\n\r\n", 44),
       400, "X-A"},
      {"no Host", "GET /healthz HTTP/1.1\r\n\r\n", 400, "Host"},
      {"two Hosts", "GET /healthz HTTP/1.1\r\nHost: a\r\nHost: b\r\n\r\n", 400, "Host"},
      {"header line past the limit",
       "GET /healthz HTTP/1.1\r\nHost: t\r\nX-Big: " + std::string(9000, 'a') + "\r\n\r\n", 431,
       "X-Big"},
      {"too many header lines",
       [] {
         std::string request = "GET /healthz HTTP/1.1\r\nHost: t\r\n";
         for (int i = 0; i < 150; ++i) request += "X-" + std::to_string(i) + ": 1\r\n";
         return request + "\r\n";
       }(),
       431, "head"},
      {"request line past the limit", "GET /" + std::string(9000, 'a') + " HTTP/1.1\r\n\r\n", 414,
       "request-line"},
      {"HTTP/2.0 request line", "GET /healthz HTTP/2.0\r\nHost: t\r\n\r\n", 505, "request-line"},
      {"garbage request line", "HELLO\r\n\r\n", 400, "request-line"},
  };
  for (const FramingCase& framing : cases) {
    SCOPED_TRACE(framing.name);
    const Exchange exchange = sendRaw(daemon().port(), framing.request);
    EXPECT_EQ(exchange.firstStatus(), framing.status) << exchange.bytes;
    EXPECT_EQ(exchange.statusCount(), 1) << "a second request was parsed:\n" << exchange.bytes;
    EXPECT_TRUE(exchange.closedByServer);
    const std::size_t body = exchange.bytes.find("\r\n\r\n");
    ASSERT_NE(body, std::string::npos);
    const json error = json::parse(exchange.bytes.substr(body + 4))["error"];
    EXPECT_EQ(error["field"], framing.field) << error.dump();
  }
  expectAlive();
}

// A chunked body is refused before it is read (411), whatever its chunk sizes say, and its bytes
// are never parsed as a request of their own.
TEST(HttpFraming, ChunkedBodiesAreRefusedUnreadAndTheConnectionClosed) {
  const Exchange exchange =
      sendRaw(daemon().port(),
              "POST /v1/render HTTP/1.1\r\nHost: t\r\nTransfer-Encoding: chunked\r\n\r\n"
              "ZZZ\r\nnot a chunk\r\n0\r\n\r\n" +
                  kHealth);
  EXPECT_EQ(exchange.firstStatus(), 411) << exchange.bytes;
  EXPECT_EQ(exchange.statusCount(), 1) << exchange.bytes;
  EXPECT_TRUE(exchange.closedByServer);
  expectAlive();
}

// A GET with a body (httplib reads no body for GET) and a refused request with a body (401 before
// the body is read): either way the body stays unread, so the connection closes after the answer
// and the request hidden in the body is never answered.
TEST(HttpFraming, UnreadBodiesNeverBecomeRequests) {
  const std::string smuggled = "GET /v1/info HTTP/1.1\r\nHost: t\r\n\r\n";
  const Exchange get = sendRaw(daemon().port(),
                               "GET /healthz HTTP/1.1\r\nHost: t\r\n"
                               "Content-Length: " +
                                   std::to_string(smuggled.size()) + "\r\n\r\n" + smuggled);
  EXPECT_EQ(get.firstStatus(), 200) << get.bytes;
  EXPECT_EQ(get.statusCount(), 1) << get.bytes;
  EXPECT_TRUE(get.closedByServer);

  DaemonProcess guarded({"--auth-token", "sekrit"});
  const Exchange refused = sendRaw(guarded.port(),
                                   "POST /v1/render HTTP/1.1\r\nHost: t\r\n"
                                   "Content-Length: " +
                                       std::to_string(smuggled.size()) + "\r\n\r\n" + smuggled);
  EXPECT_EQ(refused.firstStatus(), 401) << refused.bytes;
  EXPECT_EQ(refused.statusCount(), 1) << refused.bytes;
  EXPECT_TRUE(refused.closedByServer);
}

TEST(HttpFraming, WellFormedRequestsKeepTheConnection) {
  const Exchange pipelined = sendRaw(daemon().port(), "\r\n" + kHealth + kHealth);
  EXPECT_EQ(pipelined.statusCount(), 2) << pipelined.bytes;
  EXPECT_FALSE(pipelined.closedByServer);
  const std::string body = R"({"output": {"width": 8, "height": 8}})";
  const Exchange render =
      sendRaw(daemon().port(),
              "POST /v1/render HTTP/1.1\r\nHost: t\r\nContent-Type: application/json\r\n"
              "Accept: application/json\r\nContent-Length: " +
                  std::to_string(body.size()) + "\r\n\r\n" + body + kHealth);
  EXPECT_EQ(render.firstStatus(), 200) << render.bytes.substr(0, 300);
  EXPECT_EQ(render.statusCount(), 2);
  EXPECT_FALSE(render.closedByServer);
}

// --- Nesting ------------------------------------------------------------------------------------

TEST(HostileRequests, DeepNestingIs413ByBodyAndByMultipartPart) {
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  auto http = daemon().client();
  const auto body = http->Post("/v1/render", R"({"lights": )" + deep + "}", "application/json");
  const json error = expectError(body, 413, "too_large");
  EXPECT_NE(error["message"].get<std::string>().find("32 levels"), std::string::npos);
  httplib::MultipartFormDataItems items = {
      {"request", R"({"x": )" + deep + "}", "", "application/json"}};
  const auto part = http->Post("/v1/render", items);
  const json partError = expectError(part, 413, "too_large");
  EXPECT_EQ(partError["field"], "request");
  expectAlive();
}

// --- Hostile assets ----------------------------------------------------------------------------

fs::path hostileDir() { return fs::path(LGH_TEST_DATA_DIR) / "gltf_validator" / "hostile"; }

// The hostile assets lghd renders (each valid, or with a repair): everything else must be a 4xx.
bool rendersFine(const std::string& name) {
  return name == "glb_valid.glb" || name == "glb_unknown_chunk_after_bin.glb" ||
         name == "extras_60_deep.gltf" || name == "accessor_no_view_huge_count.gltf";
}

TEST(HostileAssets, EveryHostileAssetIsAClientErrorByPathAndByUpload) {
  const fs::path into = assetRoot().root / "hostile";
  fs::create_directories(into);
  std::size_t assets = 0;
  auto http = daemon().client(std::chrono::seconds(120));
  for (const auto& entry : fs::directory_iterator(hostileDir())) {
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    fs::copy_file(entry.path(), into / name, fs::copy_options::overwrite_existing);
    ++assets;
    const json request = {{"scene", {{"asset", "hostile/" + name}}},
                          {"output", {{"width", 16}, {"height", 16}}}};
    const auto byPath = postJson(*http, "/v1/render", request);
    ASSERT_TRUE(byPath) << "no answer: the daemon died?\n" << daemon().log();
    httplib::MultipartFormDataItems items = {
        requestPart({{"output", {{"width", 16}, {"height", 16}}}}),
        {"file", readFile(entry.path()), name, "application/octet-stream"}};
    const auto byUpload = http->Post("/v1/render", items);
    ASSERT_TRUE(byUpload) << "no answer: the daemon died?\n" << daemon().log();
    for (const auto* answer : {&byPath, &byUpload}) {
      if (rendersFine(name)) {
        EXPECT_EQ((*answer)->status, 200) << (*answer)->body.substr(0, 300);
      } else {
        EXPECT_GE((*answer)->status, 400) << (*answer)->body.substr(0, 300);
        EXPECT_LT((*answer)->status, 500) << (*answer)->body.substr(0, 300);
        EXPECT_TRUE(errorOf(*answer).contains("message"));
      }
    }
  }
  EXPECT_GE(assets, 60U);
  expectAlive();
}

// --- The scene parser worker --------------------------------------------------------------------

TEST(SceneWorker, AParserCrashCostsOneRequestNotTheDaemon) {
  DaemonProcess crashing({"--test-scene-worker-crash-marker", "Cameras"});
  auto http = crashing.client(std::chrono::seconds(120));
  const auto crashed =
      postJson(*http, "/v1/render",
               {{"scene", {{"asset", "cameras/Cameras.gltf"}}}, {"output", {{"width", 16}}}});
  const json error = expectError(crashed, 422, "invalid");
  EXPECT_NE(error["message"].get<std::string>().find("crashed the scene parser"), std::string::npos)
      << error.dump();
  const auto next = postJson(
      *http, "/v1/render",
      {{"scene", {{"asset", "BoxTextured-glTF/BoxTextured.gltf"}}}, {"output", {{"width", 16}}}});
  ASSERT_TRUE(next);
  EXPECT_EQ(next->status, 200) << next->body.substr(0, 300);
  EXPECT_FALSE(crashing.exited());
  EXPECT_NE(crashing.log().find("scene worker: crashed parsing Cameras.gltf"), std::string::npos);
}

// In a batch, scenes parse ahead on prefetch threads: a parser that crashes there is replaced
// from one of those short-lived threads, and the replacement must outlive it (a worker dies with
// the thread that started it unless started from one that lives on). Only the crashing asset
// fails; so does nothing else with three parsers side by side.
TEST(SceneWorker, AParserCrashInABatchCostsOnlyThatThumbnail) {
  for (const char* parsers : {"1", "3"}) {
    DaemonProcess crashing({"--test-scene-worker-crash-marker", "Cameras", "--scene-parsers",
                            parsers, "--scene-cache-mb", "0"});
    auto http = crashing.client(std::chrono::seconds(120));
    const json batch = {
        {"assets",
         {"BoxTextured-glTF-Binary/BoxTextured.glb", "cameras/Cameras.gltf",
          "BoxTextured-glTF/BoxTextured.gltf", "BoxTexcoords-glTF/boxTexcoords.gltf",
          "BoxTextured-glTF-Embedded/BoxTextured.gltf",
          "2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
          "BoxTextured-glTF-Binary/BoxTextured.glb"}},
        {"width", 16},
        {"height", 16},
        {"name_template", "{index}.png"}};
    const auto result = postJson(*http, "/v1/thumbnails", batch);
    ASSERT_TRUE(result);
    ASSERT_EQ(result->status, 200) << result->body.substr(0, 300);
    const auto members = unzip(result->body);
    EXPECT_EQ(result->get_header_value("X-Lgh-Thumbnails-Failed"), "1")
        << parsers
        << " parsers: " << (members.contains("errors.json") ? members.at("errors.json") : "");
    EXPECT_EQ(result->get_header_value("X-Lgh-Thumbnails-Ok"), "6") << parsers << " parsers";
    EXPECT_FALSE(members.contains("1.png"));
    EXPECT_FALSE(crashing.exited());
  }
}

TEST(SceneWorker, AParseRunningPastItsTimeIs413AndTheNextLoadWorks) {
  DaemonProcess slow({"--scene-worker-timeout-seconds", "0.1"});
  auto http = slow.client(std::chrono::seconds(120));
  // Three million vertices from a few bytes of JSON: far more than 0.1 s of work.
  const std::string huge =
      R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
          "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
          "accessors": [{"componentType": 5126, "count": 3000000, "type": "VEC3",
                         "min": [0, 0, 0], "max": [0, 0, 0]}]})";
  httplib::MultipartFormDataItems items = {{"file", huge, "huge.gltf", "model/gltf+json"}};
  const json error = expectError(http->Post("/v1/render", items), 413, "too_large");
  EXPECT_NE(error["message"].get<std::string>().find("limit of 0.1 s"), std::string::npos);
  const auto next = postJson(
      *http, "/v1/render",
      {{"scene", {{"asset", "BoxTextured-glTF/BoxTextured.gltf"}}}, {"output", {{"width", 16}}}});
  ASSERT_TRUE(next);
  EXPECT_EQ(next->status, 200) << next->body.substr(0, 300);
}

// --- Operations ---------------------------------------------------------------------------------

TEST(Operations, WarningHeadersAreCappedAndTheBodyHasThemAll) {
  // 300 optional extensions lghd does not know: one warning each, about 20 KB in all.
  json gltf = json::parse(readFile(assimpDir() / "BoxTextured-glTF-Embedded/BoxTextured.gltf"));
  for (int i = 0; i < 300; ++i) {
    gltf["extensionsUsed"].push_back("EXT_made_up_for_lghd_header_cap_test_" + std::to_string(i));
  }
  httplib::MultipartFormDataItems items = {
      requestPart({{"output", {{"width", 16}, {"height", 16}}}}),
      {"file", gltf.dump(), "box.gltf", "model/gltf+json"}};
  auto http = daemon().client(std::chrono::seconds(120));
  const auto image = http->Post("/v1/render", items);
  ASSERT_TRUE(image);
  ASSERT_EQ(image->status, 200) << image->body.substr(0, 300);
  const std::string warnings = image->get_header_value("X-Lgh-Warnings");
  EXPECT_LE(warnings.size(), 2048U);
  const json header = json::parse(warnings);
  ASSERT_TRUE(header.is_array());
  EXPECT_NE(header.back().get<std::string>().find("more (the JSON body"), std::string::npos);
  const auto full = http->Post("/v1/render", {{"Accept", "application/json"}}, items);
  ASSERT_TRUE(full);
  ASSERT_EQ(full->status, 200);
  EXPECT_GE(json::parse(full->body)["warnings"].size(), 300U);
  EXPECT_LE(full->get_header_value("X-Lgh-Warnings").size(), 2048U);
}

TEST(Operations, MetricsPortServesScrapesWithoutTheToken) {
  DaemonProcess guarded({"--auth-token", "sekrit", "--metrics-port", "0"});
  ASSERT_GT(guarded.metricsPort(), 0);
  httplib::Client scraper("127.0.0.1", guarded.metricsPort());
  const auto metrics = scraper.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_EQ(metrics->status, 200);
  EXPECT_NE(metrics->body.find("lghd_build_info"), std::string::npos);
  EXPECT_EQ(scraper.Get("/readyz")->status, 200);
  EXPECT_EQ(scraper.Get("/v1/info")->status, 404);  // nothing but scrapes and probes there
  EXPECT_EQ(scraper.Post("/v1/render", "{}", "application/json")->status, 404);
  auto main = guarded.client();
  EXPECT_EQ(main->Get("/metrics")->status, 401);  // the main port still wants the token
}

}  // namespace
}  // namespace lghd::test
