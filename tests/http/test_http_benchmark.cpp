// POST /v1/benchmark through the real daemon: a small `lgh-bench gi` suite runs in a child process
// with progress on GET /v1/benchmark, one at a time (429 with Retry-After while it runs), mistakes
// are answered at once naming the field, and the document of GET /v1/benchmark/result has the
// very shape and settings of `lgh-bench gi --json` run with the same options (the timings differ
// from run to run; the keys, the settings, the device and the configurations do not).
#include <gtest/gtest.h>

#include <cstdio>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "daemon_process.hpp"
#include "http_helpers.hpp"

namespace {

using json = nlohmann::json;
using lghd::test::DaemonProcess;

// The smallest suite that runs every part: Table 2 and 3 at one VPL count, Fig. 5's overdraw,
// the quality runs with both references.
const json kBody = {
    {"vpls", {1000}},         {"width", 64},         {"height", 36},    {"table3_vpls", 1000},
    {"interleave", {"none"}}, {"iterations", 1},     {"warmup", 0},     {"quality_width", 16},
    {"quality_height", 9},    {"quality_vpls", 500}, {"pt_samples", 4}, {"quality_alphas", {2}}};
const std::string kFlags =
    "--vpls 1000 --width 64 --height 36 --table3-vpls 1000 --interleave none --iterations 1 "
    "--warmup 0 --quality-width 16 --quality-height 9 --quality-vpls 500 --pt-samples 4 "
    "--quality-alphas 2";

// Where the two documents may differ: measured values. Everything else (keys, array lengths,
// strings, booleans, integers that describe the configuration) must match.
void expectSameShape(const json& a, const json& b, const std::string& at) {
  ASSERT_EQ(a.type(), b.type()) << at << ": " << a.dump().substr(0, 80) << " vs "
                                << b.dump().substr(0, 80);
  if (a.is_object()) {
    for (const auto& [key, value] : a.items()) {
      ASSERT_TRUE(b.contains(key)) << at << "/" << key << " missing from the CLI's document";
      expectSameShape(value, b.at(key), fmt::format("{}/{}", at, key));
    }
    for (const auto& [key, value] : b.items()) {
      EXPECT_TRUE(a.contains(key)) << at << "/" << key << " missing from the daemon's document";
    }
  } else if (a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << at;
    for (std::size_t i = 0; i < a.size(); ++i) {
      expectSameShape(a[i], b[i], fmt::format("{}/{}", at, i));
    }
  } else if (a.is_string() || a.is_boolean()) {
    // Names of passes, paths, interleavings, devices: the same run, the same words.
    EXPECT_EQ(a, b) << at;
  }
}

json runCli() {
  const std::string command = fmt::format("{} gi {} --json 2>/dev/null", LGH_BENCH_BINARY, kFlags);
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return nullptr;
  std::string output;
  char buffer[4096];
  std::size_t got = 0;
  while ((got = fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, got);
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << command;
  return json::parse(output);
}

json waitForEnd(httplib::Client& http) {
  for (int i = 0; i < 1200; ++i) {
    const auto status = http.Get("/v1/benchmark");
    if (!status || status->status != 200) return nullptr;
    json body = json::parse(status->body);
    if (body.at("status") != "running") return body;
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  return nullptr;
}

TEST(HttpBenchmark, RunsTheCliSuiteOneAtATimeWithProgress) {
  DaemonProcess daemon;
  auto http = daemon.client();
  EXPECT_EQ(json::parse(http->Get("/v1/benchmark")->body).at("status"), "idle");
  lghd::test::expectError(http->Get("/v1/benchmark/result"), 404, "not_found");

  const auto started = lghd::test::postJson(*http, "/v1/benchmark", kBody);
  ASSERT_TRUE(started);
  ASSERT_EQ(started->status, 202) << started->body;
  EXPECT_EQ(started->get_header_value("Location"), "/v1/benchmark");
  EXPECT_EQ(json::parse(started->body).at("status"), "running");
  // A GL context, shaders and a Vulkan device take the child well over the next request's time.
  const auto second = lghd::test::postJson(*http, "/v1/benchmark", kBody);
  lghd::test::expectError(second, 429, "queue_full");
  EXPECT_FALSE(second->get_header_value("Retry-After").empty());

  const json end = waitForEnd(*http);
  ASSERT_EQ(end.value("status", ""), "done") << end.dump(2) << "\n" << daemon.log();
  EXPECT_GE(end.at("progress").at("steps").get<int>(), 3) << end.dump(2);
  const auto result = http->Get("/v1/benchmark/result");
  ASSERT_EQ(result->status, 200);
  EXPECT_EQ(result->get_header_value("Content-Type"), "application/json");
  const json fromDaemon = json::parse(result->body);
  EXPECT_EQ(fromDaemon.at("benchmark"), "lgh-gi");

  const json fromCli = runCli();
  expectSameShape(fromDaemon, fromCli, "");
  EXPECT_EQ(fromDaemon.at("settings"), fromCli.at("settings"));
  EXPECT_EQ(fromDaemon.at("device"), fromCli.at("device"));
}

TEST(HttpBenchmark, MistakesAreAnsweredAtOnceNamingTheField) {
  DaemonProcess daemon({"--max-vpls", "100000"});
  auto http = daemon.client();
  const auto unknown = lghd::test::postJson(*http, "/v1/benchmark", {{"vpl", {1000}}});
  EXPECT_EQ(lghd::test::expectError(unknown, 400, "bad_request").at("field"), "/vpl");
  const auto type = lghd::test::postJson(*http, "/v1/benchmark", {{"width", "wide"}});
  EXPECT_EQ(lghd::test::expectError(type, 400, "bad_request").at("field"), "/width");
  const auto range = lghd::test::postJson(*http, "/v1/benchmark", {{"bounces", 4}});
  EXPECT_EQ(lghd::test::expectError(range, 422, "invalid").at("field"), "/bounces");
  const auto alphas =
      lghd::test::postJson(*http, "/v1/benchmark", {{"vpls", {1000}}, {"quality_alphas", {2, -1}}});
  EXPECT_EQ(lghd::test::expectError(alphas, 422, "invalid").at("field"), "/quality_alphas/1");
  const auto jitter =
      lghd::test::postJson(*http, "/v1/benchmark", {{"vpls", {1000}}, {"shadow_jitter", 2}});
  EXPECT_EQ(lghd::test::expectError(jitter, 422, "invalid").at("field"), "/shadow_jitter");
  const auto scene = lghd::test::postJson(*http, "/v1/benchmark", {{"scene", "nave"}});
  EXPECT_EQ(lghd::test::expectError(scene, 422, "invalid").at("field"), "/scene");
  // The default VPL counts reach 1M, over this daemon's limit.
  const auto defaults = lghd::test::postJson(*http, "/v1/benchmark", json::object());
  EXPECT_EQ(lghd::test::expectError(defaults, 413, "too_large").at("field"), "/vpls");
  const auto many = lghd::test::postJson(*http, "/v1/benchmark", {{"vpls", {1000, 200000}}});
  EXPECT_EQ(lghd::test::expectError(many, 413, "too_large").at("field"), "/vpls/1");
  // Nothing started.
  EXPECT_EQ(json::parse(http->Get("/v1/benchmark")->body).at("status"), "idle");
}

}  // namespace
