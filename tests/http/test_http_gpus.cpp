// Several render workers in one lghd (--gpus 0,0,0: three llvmpipe contexts on the one EGL device
// here, as on a node with three GPUs): renders spread over the workers and name the one they ran
// on, a thumbnail batch split over them comes back complete, in order and equal to one worker's,
// deadlines and a client that goes away still work, and one worker's lost context fails only its
// render while the others serve. --test-render-delay-ms makes renders overlap on purpose.
#include <gtest/gtest.h>

#include <cmath>
#include <future>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "daemon_process.hpp"
#include "http_helpers.hpp"
#include "lgh/base64.hpp"

namespace lghd::test {
namespace {

const json kSmallDemo = {{"output", {{"width", 48}, {"height", 32}}}};

std::vector<json> ndjsonLines(const std::string& body) {
  std::vector<json> lines;
  std::istringstream stream(body);
  for (std::string line; std::getline(stream, line);) {
    if (!line.empty()) lines.push_back(json::parse(line));
  }
  return lines;
}

std::string unbase64(const json& text) {
  const auto decoded = lgh::base64::decode(text.get<std::string>());
  const auto* bytes = std::get_if<std::vector<std::uint8_t>>(&decoded);
  return bytes != nullptr ? std::string(bytes->begin(), bytes->end()) : std::string();
}

struct Rendered {
  int status = 0;
  std::string gpu;
  std::string body;
};

// `count` renders of the small demo from `count` clients at once.
std::vector<Rendered> concurrentRenders(const DaemonProcess& daemon, int count) {
  std::vector<std::future<Rendered>> futures;
  futures.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    futures.push_back(std::async(std::launch::async, [&daemon] {
      auto http = daemon.client();
      const auto result = postJson(*http, "/v1/render", kSmallDemo);
      if (!result) return Rendered{};
      return Rendered{result->status, result->get_header_value("X-Lgh-Gpu"), result->body};
    }));
  }
  std::vector<Rendered> results;
  results.reserve(futures.size());
  for (auto& future : futures) results.push_back(future.get());
  return results;
}

bool waitForAllReady(httplib::Client& http, std::size_t workers) {
  for (int i = 0; i < 600; ++i) {
    const auto ready = http.Get("/readyz");
    if (ready && ready->status == 200) {
      const json body = json::parse(ready->body);
      std::size_t up = 0;
      for (const json& gpu : body["gpus"]) up += gpu["state"] == "ready" ? 1 : 0;
      if (up == workers) return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

// Mean absolute difference (0..255) of two 8-bit PNGs of the same size (255: they differ in size).
double meanDifference(const std::string& a, const std::string& b) {
  const auto first = decodeBody(a, "first");
  const auto second = decodeBody(b, "second");
  if (first.width != second.width || first.pixels8.size() != second.pixels8.size()) return 255.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < first.pixels8.size(); ++i) {
    sum += std::abs(int{first.pixels8[i]} - int{second.pixels8[i]});
  }
  return sum / static_cast<double>(std::max<std::size_t>(first.pixels8.size(), 1));
}

std::string thumbnailsNdjson(httplib::Client& http, const json& request) {
  const auto result = postJson(http, "/v1/thumbnails", request);
  if (!result || result->status != 200) {
    ADD_FAILURE() << (result ? result->body : "no answer");
    return "";
  }
  return result->body;
}

class GpusTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    daemon = new DaemonProcess({"--gpus", "0,0,0", "--test-render-delay-ms", "60"});
  }
  static void TearDownTestSuite() {
    delete daemon;
    daemon = nullptr;
  }
  // /readyz answers 200 once one worker is up: the tests want all of them.
  void SetUp() override {
    http = daemon->client();
    ASSERT_TRUE(waitForAllReady(*http, 3)) << daemon->log();
  }
  void TearDown() override {
    if (HasFailure()) std::cerr << "--- lghd log ---\n" << daemon->log();
  }

  static DaemonProcess* daemon;
  std::unique_ptr<httplib::Client> http;
};
DaemonProcess* GpusTest::daemon = nullptr;

TEST_F(GpusTest, InfoAndReadyzListEachWorker) {
  ASSERT_TRUE(waitForAllReady(*http, 3));
  const json info = json::parse(http->Get("/v1/info")->body);
  ASSERT_EQ(info["gpus"].size(), 3U) << info.dump();
  for (int i = 0; i < 3; ++i) {
    const json& gpu = info["gpus"][i];
    EXPECT_EQ(gpu["gpu"], i);
    EXPECT_EQ(gpu["device_index"], 0);
    EXPECT_EQ(gpu["state"], "ready");
    EXPECT_FALSE(gpu["device_name"].get<std::string>().empty());
    EXPECT_TRUE(gpu["scene_cache"].contains("budget_bytes"));
    EXPECT_TRUE(gpu["queue_depth"].is_number());
  }
  const std::string metrics = http->Get("/metrics")->body;
  EXPECT_EQ(metricValue(metrics, "lghd_gpu_ready{gpu=\"2\"}"), 1.0);
  EXPECT_EQ(metricValue(metrics, "lghd_ready"), 1.0);
}

TEST_F(GpusTest, ConcurrentRendersSpreadOverTheWorkersAndNameTheirGpu) {
  const std::string before = http->Get("/metrics")->body;
  const std::vector<Rendered> results = concurrentRenders(*daemon, 9);
  std::map<std::string, int> perGpu;
  for (const Rendered& result : results) {
    ASSERT_EQ(result.status, 200) << result.body;
    ++perGpu[result.gpu];
  }
  EXPECT_GE(perGpu.size(), 2U) << "nine overlapping renders should not all go to one worker";
  for (const auto& [gpu, count] : perGpu) {
    ASSERT_TRUE(gpu == "0" || gpu == "1" || gpu == "2") << gpu;
    const std::string series = "lghd_gpu_renders_total{gpu=\"" + gpu + "\",outcome=\"ok\"}";
    EXPECT_EQ(waitForMetric(*http, series, metricValue(before, series) + count),
              metricValue(before, series) + count)
        << series;
  }
  // The JSON answer names it too.
  const auto asJson = postJson(*http, "/v1/render", kSmallDemo, {{"Accept", "application/json"}});
  ASSERT_EQ(asJson->status, 200);
  const json body = json::parse(asJson->body);
  EXPECT_EQ(std::to_string(body["gpu"].get<int>()), asJson->get_header_value("X-Lgh-Gpu"));
  // The EGL device, where the context path has one (surfaceless and OSMesa have none).
  const json info = json::parse(http->Get("/v1/info")->body);
  const int device = info["device"].value("egl_device_index", -1);
  EXPECT_EQ(asJson->has_header("X-Lgh-Gpu-Device"), device >= 0);
  if (device >= 0) EXPECT_EQ(asJson->get_header_value("X-Lgh-Gpu-Device"), "0");
}

TEST_F(GpusTest, ASplitBatchComesBackCompleteInOrderAndEqualToOneWorkersImages) {
  const json request = {
      {"assets",
       {"BoxTextured-glTF-Binary/BoxTextured.glb", "missing/Nothing.glb",
        "BoxTextured-glTF/BoxTextured.gltf", "2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
        "BoxTextured-glTF-Embedded/BoxTextured.gltf", "BoxTexcoords-glTF/boxTexcoords.gltf"}},
      {"views",
       {{{"name", "front"}, {"direction", {0, 0, 1}}},
        {{"name", "side"}, {"direction", {1, 0.5, 0}}}}},
      {"width", 40},
      {"height", 40},
      {"format", "ndjson"}};
  const std::vector<json> lines = ndjsonLines(thumbnailsNdjson(*http, request));
  const DaemonProcess single({"--gpus", "0"});
  auto singleHttp = single.client();
  const std::vector<json> reference = ndjsonLines(thumbnailsNdjson(*singleHttp, request));
  ASSERT_EQ(lines.size(), 13U);  // 6 assets x 2 views, then the summary
  ASSERT_EQ(reference.size(), lines.size());
  std::set<int> gpus;
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_EQ(lines[i]["index"], i);
    EXPECT_EQ(lines[i]["file"], reference[i]["file"]);
    EXPECT_EQ(lines[i]["status"], reference[i]["status"]) << lines[i].dump().substr(0, 300);
    if (lines[i]["status"] != "ok") continue;
    gpus.insert(lines[i]["gpu"].get<int>());
    EXPECT_EQ(reference[i]["gpu"], 0);
    EXPECT_LE(
        meanDifference(unbase64(lines[i]["image_base64"]), unbase64(reference[i]["image_base64"])),
        0.5)
        << lines[i]["file"];
  }
  EXPECT_EQ(lines[2]["status"], "error") << "the missing asset";
  EXPECT_GE(gpus.size(), 2U) << "the batch should be split over the workers";
  EXPECT_EQ(lines[12]["status"], "done");
  EXPECT_EQ(lines[12]["ok"], 10);
  EXPECT_EQ(lines[12]["failed"], 2);
}

// In a ZIP answer each thumbnail names its GPU in its file comment, as an NDJSON line does.
TEST_F(GpusTest, ZipThumbnailsNameTheirGpuInTheirComments) {
  const json request = {
      {"assets",
       {"BoxTextured-glTF-Binary/BoxTextured.glb", "missing/Nothing.glb",
        "BoxTextured-glTF/BoxTextured.gltf", "BoxTexcoords-glTF/boxTexcoords.gltf",
        "BoxTextured-glTF-Embedded/BoxTextured.gltf"}},
      {"width", 32},
      {"height", 32},
      {"name_template", "{index}.png"}};
  const auto result = postJson(*http, "/v1/thumbnails", request);
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  const auto comments = zipComments(result->body);
  EXPECT_EQ(comments.size(), 5U) << "four thumbnails and errors.json";
  std::set<int> gpus;
  for (const auto& [name, comment] : comments) {
    if (name == "errors.json") {
      EXPECT_EQ(comment, "");
      continue;
    }
    const json named = json::parse(comment, nullptr, false);
    ASSERT_TRUE(named.is_object() && named.contains("gpu")) << name << ": " << comment;
    EXPECT_EQ(named.size(), 1U) << comment;
    gpus.insert(named["gpu"].get<int>());
  }
  EXPECT_GE(gpus.size(), 2U) << "the batch should be split over the workers";
  for (int gpu : gpus) EXPECT_TRUE(gpu >= 0 && gpu < 3) << gpu;
}

// Deadlines and a client that goes away, with two workers kept busy.
TEST(GpusDeadlines, QueueAndRenderDeadlinesAndACancelledBatchStillWork) {
  DaemonProcess daemon({"--gpus", "0,0", "--test-render-delay-ms", "700"});
  auto http = daemon.client();
  ASSERT_TRUE(waitForAllReady(*http, 2)) << daemon.log();
  // Two slow renders keep both workers busy; a third with a short deadline waits in a queue.
  auto busy = std::async(std::launch::async, [&daemon] { return concurrentRenders(daemon, 2); });
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  const auto late = postJson(*http, "/v1/render", kSmallDemo, {{"X-Lgh-Deadline-Ms", "200"}});
  ASSERT_TRUE(late);
  EXPECT_EQ(late->status, 504) << late->body;
  for (const Rendered& result : busy.get()) EXPECT_EQ(result.status, 200) << result.body;
  EXPECT_GE(waitForMetric(*http, "lghd_renders_total{outcome=\"skipped\"}", 1), 1)
      << "the late render expired in its worker's queue and was not rendered\n"
      << http->Get("/metrics")->body << daemon.log();

  // A batch whose client reads one line and goes away: the renders not started are skipped.
  const double skippedBefore =
      metricValue(http->Get("/metrics")->body, "lghd_renders_total{outcome=\"skipped\"}");
  json assets = json::array();
  // Enough renders that both workers still have unstarted ones when the daemon finds out (its
  // write of a later line fails only once the client's side has closed).
  for (int i = 0; i < 20; ++i) assets.push_back("BoxTextured-glTF-Binary/BoxTextured.glb");
  const json request = {{"assets", assets},
                        {"views", {{{"name", "a"}, {"direction", {0, 0, 1}}}}},
                        {"width", 32},
                        {"height", 32},
                        {"format", "ndjson"}};
  httplib::Request streamed;
  streamed.method = "POST";
  streamed.path = "/v1/thumbnails";
  streamed.body = request.dump();
  streamed.set_header("Content-Type", "application/json");
  std::string received;
  streamed.content_receiver = [&](const char* data, std::size_t length, std::uint64_t,
                                  std::uint64_t) {
    received.append(data, length);
    return received.find('\n') == std::string::npos;  // stop after the first line
  };
  httplib::Response response;
  httplib::Error error = httplib::Error::Success;
  auto streamClient = daemon.client();
  streamClient->send(streamed, response, error);
  ASSERT_NE(received.find("\"gpu\""), std::string::npos) << received.substr(0, 200);
  EXPECT_GE(waitForMetric(*http, "lghd_renders_total{outcome=\"skipped\"}", skippedBefore + 1),
            skippedBefore + 1)
      << daemon.log();
  // Both workers serve on.
  const auto after = postJson(*http, "/v1/render", kSmallDemo);
  ASSERT_TRUE(after);
  EXPECT_EQ(after->status, 200) << after->body;
}

TEST(GpusRecovery, OneWorkersLostContextFailsOnlyItsRenderAndTheOthersServe) {
  // Worker 1's first renderer reports a loss on its first frame after the self-test.
  DaemonProcess daemon(
      {"--gpus", "0,0", "--test-context-loss", "1:1", "--test-render-delay-ms", "150"});
  auto http = daemon.client();
  ASSERT_TRUE(waitForAllReady(*http, 2)) << daemon.log();
  const std::vector<Rendered> results = concurrentRenders(daemon, 4);
  int lost = 0;
  for (const Rendered& result : results) {
    if (result.status == 503) {
      ++lost;
      EXPECT_NE(result.body.find("GL context was lost"), std::string::npos) << result.body;
    } else {
      EXPECT_EQ(result.status, 200) << result.body;
    }
  }
  EXPECT_EQ(lost, 1) << daemon.log();
  EXPECT_EQ(http->Get("/readyz")->status, 200) << "worker 0 serves while worker 1 is rebuilt";
  ASSERT_TRUE(waitForAllReady(*http, 2)) << daemon.log();
  EXPECT_NE(daemon.log().find("renderer_reset"), std::string::npos);
  // The rebuilt worker takes renders again.
  std::set<std::string> gpus;
  for (int round = 0; round < 5 && gpus.size() < 2; ++round) {
    for (const Rendered& result : concurrentRenders(daemon, 4)) {
      EXPECT_EQ(result.status, 200) << result.body;
      gpus.insert(result.gpu);
    }
  }
  EXPECT_EQ(gpus, (std::set<std::string>{"0", "1"}));
}

}  // namespace
}  // namespace lghd::test
