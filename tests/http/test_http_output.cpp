// The output pipeline of the real daemon (docs/DAEMON.md, "Frames in flight"): frames submitted
// back to back, read back asynchronously, encoded on the encoder pool.
//  - many concurrent clients, each with its own size, format and background colour, each get
//    their own image back (checked by content, not by status alone);
//  - a render past its deadline while its frame is in flight is answered 504, and its frame's
//    read-back memory comes back; so does a streamed batch whose client hangs up;
//  - the queue and encode rows and metrics are there.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "daemon_process.hpp"
#include "http_helpers.hpp"
#include "lgh/image.hpp"

namespace lghd::test {
namespace {

const char* kBox = "BoxTextured-glTF-Binary/BoxTextured.glb";

// Polls /metrics until `done` holds for the exposition, up to `timeout`; returns the last one.
template <typename Predicate>
std::string waitForMetrics(httplib::Client& client, Predicate done,
                           std::chrono::seconds timeout = std::chrono::seconds(60)) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  std::string text;
  do {
    if (auto answer = client.Get("/metrics"); answer && answer->status == 200) {
      text = answer->body;
      if (done(text)) return text;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  } while (std::chrono::steady_clock::now() < until);
  return text;
}

bool outputIdle(const std::string& metrics) {
  return metricValue(metrics, "lghd_frames_in_flight") == 0 &&
         metricValue(metrics, "lghd_readback_bytes") == 0;
}

struct ClientCase {
  int width;
  int height;
  std::string format;
  std::array<float, 3> background;
};

ClientCase caseFor(int client, int round) {
  const int k = client * 3 + round;
  static const char* kFormats[] = {"png", "exr", "exr-float"};
  return {40 + 4 * (k % 9),
          24 + 2 * (k % 7),
          kFormats[k % 3],
          {static_cast<float>(client) / 16.0F, 0.2F + 0.1F * static_cast<float>(round),
           1.0F - static_cast<float>(client) / 16.0F}};
}

// What the top-left (background) pixel must be: the display codes of the background for a PNG
// (ACES, the default), the linear colour for an EXR.
std::string checkImage(const ClientCase& expected, const httplib::Result& answer) {
  if (!answer) return "no answer";
  if (answer->status != 200) return fmt::format("status {}: {}", answer->status, answer->body);
  const bool png = expected.format == "png";
  if (answer->get_header_value("Content-Type") != (png ? "image/png" : "image/x-exr")) {
    return "content type " + answer->get_header_value("Content-Type");
  }
  const lgh::image_io::Decoded image = decodeBody(answer->body);
  if (image.width != expected.width || image.height != expected.height) {
    return fmt::format("{}x{}, not {}x{}", image.width, image.height, expected.width,
                       expected.height);
  }
  if (png) {
    lgh::FloatImage background{
        1, 1, {expected.background[0], expected.background[1], expected.background[2], 1.0F}};
    const lgh::Image8 codes = lgh::toDisplay8(background, lgh::ToneMap::Aces, 1.0F, false);
    for (int c = 0; c < 3; ++c) {
      if (std::abs(int{image.pixels8[c]} - int{codes.pixels[c]}) > 1) {
        return fmt::format("corner channel {} is {}, not {}", c, image.pixels8[c], codes.pixels[c]);
      }
    }
    return "";
  }
  for (int c = 0; c < 3; ++c) {
    if (std::fabs(image.pixelsFloat[c] - expected.background[c]) > 2e-3F) {
      return fmt::format("corner channel {} is {}, not {}", c, image.pixelsFloat[c],
                         expected.background[c]);
    }
  }
  return "";
}

TEST(OutputPipeline, ConcurrentClientsGetTheirOwnImages) {
  DaemonProcess daemon({"--queue-depth", "64", "--encode-threads", "3", "--frames-in-flight", "4"});
  std::mutex mutex;
  std::vector<std::string> failures;
  constexpr int kClients = 12;
  std::vector<std::thread> clients;
  clients.reserve(kClients);
  for (int client = 0; client < kClients; ++client) {
    clients.emplace_back([&, client] {
      auto http = daemon.client();
      for (int round = 0; round < 3; ++round) {
        const ClientCase c = caseFor(client, round);
        const json request = {{"scene", {{"asset", kBox}}},
                              {"camera", {{"type", "auto"}, {"margin", 1.6}}},
                              {"settings", {{"shadows", "off"}}},
                              {"output",
                               {{"width", c.width},
                                {"height", c.height},
                                {"format", c.format},
                                {"background", c.background}}}};
        const std::string problem = checkImage(c, postJson(*http, "/v1/render", request));
        if (!problem.empty()) {
          std::lock_guard lock(mutex);
          failures.push_back(fmt::format("client {} round {} ({} {}x{}): {}", client, round,
                                         c.format, c.width, c.height, problem));
        }
      }
    });
  }
  for (auto& client : clients) client.join();
  for (const std::string& failure : failures) ADD_FAILURE() << failure;
  auto http = daemon.client();
  const std::string metrics = waitForMetrics(*http, outputIdle);
  EXPECT_TRUE(outputIdle(metrics)) << metrics;
  EXPECT_EQ(metricValue(metrics, "lghd_encode_threads"), 3);
  EXPECT_GE(metricValue(metrics, "lghd_encode_seconds_count{format=\"png\"}"), 12);
  EXPECT_GE(metricValue(metrics, "lghd_encode_seconds_count{format=\"exr-float\"}"), 12);
  EXPECT_GE(metricValue(metrics, "lghd_encode_wait_seconds_count"), 36);
  if (HasFailure()) std::cerr << daemon.log();
}

TEST(OutputPipeline, TimingRowsShowTheQueueAndTheEncoding) {
  DaemonProcess daemon;
  auto http = daemon.client();
  const auto answer = postJson(*http, "/v1/render", {{"output", {{"width", 32}, {"height", 32}}}});
  ASSERT_TRUE(answer);
  ASSERT_EQ(answer->status, 200);
  const json rows = json::parse(answer->get_header_value("X-Lgh-Timings"));
  std::set<std::string> names;
  for (const json& row : rows) names.insert(row["pass"].get<std::string>());
  for (const char* name : {"queue", "scene load", "upload", "submit", "direct lighting", "readback",
                           "frame wait", "encode wait", "encode", "total"}) {
    EXPECT_TRUE(names.contains(name)) << name << " in " << rows.dump();
  }
  EXPECT_EQ(answer->get_header_value("Server-Timing").rfind("queue;dur=", 0), 0U);
}

// A frame that takes longer than its deadline: the waiter answers 504 while the frame is on the
// GPU (or being read back); the encoder then drops it, and its read-back memory comes back.
TEST(OutputPipeline, DeadlinePassedInFlightFreesTheFrame) {
  DaemonProcess daemon;
  auto http = daemon.client();
  const json heavy = {{"output", {{"width", 1024}, {"height", 768}}},
                      {"settings", {{"lgh", {{"enabled", true}, {"vpl_count", 20000}}}}}};
  const auto answer = postJson(*http, "/v1/render", heavy, {{"X-Lgh-Deadline-Ms", "60"}});
  expectError(answer, 504, "timeout");
  const std::string metrics = waitForMetrics(*http, [](const std::string& text) {
    return metricValue(text, "lghd_renders_total{outcome=\"timeout\"}") >= 1 && outputIdle(text);
  });
  EXPECT_EQ(metricValue(metrics, "lghd_renders_total{outcome=\"timeout\"}"), 1) << metrics;
  EXPECT_TRUE(outputIdle(metrics)) << metrics;
  // The context is healthy for the next request.
  const auto next = postJson(*http, "/v1/render", {{"output", {{"width", 16}, {"height", 16}}}});
  ASSERT_TRUE(next);
  EXPECT_EQ(next->status, 200);
  if (HasFailure()) std::cerr << daemon.log();
}

// A streamed batch whose client hangs up after the first line: the frames in flight finish and
// give their memory back, the renders not started are skipped.
TEST(OutputPipeline, BatchCancelledMidStreamFreesItsFrames) {
  DaemonProcess daemon({"--frames-in-flight", "3"});
  json assets = json::array();
  for (int i = 0; i < 12; ++i) assets.push_back(kBox);
  const json batch = {{"assets", assets},
                      {"width", 384},
                      {"height", 384},
                      {"format", "ndjson"},
                      {"settings", {{"lgh", {{"enabled", true}, {"vpl_count", 5000}}}}}};
  {
    auto http = daemon.client();
    std::string received;
    httplib::Request request;
    request.method = "POST";
    request.path = "/v1/thumbnails";
    request.body = batch.dump();
    request.set_header("Content-Type", "application/json");
    request.content_receiver = [&](const char* data, std::size_t length, std::uint64_t,
                                   std::uint64_t) {
      received.append(data, length);
      return received.find('\n') == std::string::npos;  // hang up after the first line
    };
    httplib::Response response;
    httplib::Error error = httplib::Error::Success;
    http->send(request, response, error);
    EXPECT_NE(received.find("\"index\":0"), std::string::npos) << received.substr(0, 200);
  }
  auto http = daemon.client();
  const std::string metrics = waitForMetrics(*http, [](const std::string& text) {
    return metricValue(text, "lghd_renders_total{outcome=\"skipped\"}") >= 1 && outputIdle(text);
  });
  EXPECT_GE(metricValue(metrics, "lghd_renders_total{outcome=\"skipped\"}"), 1) << metrics;
  EXPECT_TRUE(outputIdle(metrics)) << metrics;
  if (HasFailure()) std::cerr << daemon.log();
}

}  // namespace
}  // namespace lghd::test
