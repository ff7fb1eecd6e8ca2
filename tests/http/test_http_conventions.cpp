// HTTP conventions against the real daemon: 405 with Allow, OPTIONS, Accept negotiation with
// q-values and 406 (before any render), CORS with --cors-origin (preflights answered before
// authentication), and the /metrics exposition: the process_* metrics, and promtool's verdict.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "daemon_process.hpp"
#include "http_helpers.hpp"

namespace lghd::test {
namespace {

class ConventionsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { daemon = new DaemonProcess(); }
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
DaemonProcess* ConventionsTest::daemon = nullptr;

const json kSmall = {{"output", {{"width", 16}, {"height", 8}}}};

TEST_F(ConventionsTest, WrongMethodIs405WithAllow) {
  const auto put = http->Put("/v1/render", "{}", "application/json");
  EXPECT_EQ(expectError(put, 405, "method_not_allowed")["field"], "method");
  EXPECT_EQ(put->get_header_value("Allow"), "POST, OPTIONS");
  const auto post = http->Post("/healthz", "", "application/json");
  expectError(post, 405, "method_not_allowed");
  EXPECT_EQ(post->get_header_value("Allow"), "GET, HEAD, OPTIONS");
  const auto jobs = http->Get("/v1/jobs");
  expectError(jobs, 405, "method_not_allowed");
  EXPECT_EQ(jobs->get_header_value("Allow"), "POST, OPTIONS");
  const auto job = http->Put("/v1/jobs/0123", "", "application/json");
  EXPECT_EQ(job->get_header_value("Allow"), "GET, HEAD, DELETE, OPTIONS");
  // Unknown paths stay 404; HEAD is GET without the body.
  expectError(http->Put("/nowhere", "", "application/json"), 404, "not_found");
  const auto head = http->Head("/healthz");
  ASSERT_TRUE(head);
  EXPECT_EQ(head->status, 200);
  EXPECT_TRUE(head->body.empty());
}

TEST_F(ConventionsTest, OptionsAnswersAllowWithoutCorsHeaders) {
  const auto options = http->Options("/v1/render");
  ASSERT_TRUE(options);
  EXPECT_EQ(options->status, 204);
  EXPECT_EQ(options->get_header_value("Allow"), "POST, OPTIONS");
  // No --cors-origin: no CORS header, even for a preflight from a browser.
  const auto preflight = http->Options(
      "/v1/render", {{"Origin", "https://app.example"}, {"Access-Control-Request-Method", "POST"}});
  ASSERT_TRUE(preflight);
  EXPECT_FALSE(preflight->has_header("Access-Control-Allow-Origin"));
  expectError(http->Options("/nowhere"), 404, "not_found");
}

TEST_F(ConventionsTest, AcceptIsNegotiatedWithQValues) {
  auto renderWith = [&](const std::string& accept) {
    return postJson(*http, "/v1/render", kSmall, {{"Accept", accept}});
  };
  auto typeOf = [](const httplib::Result& result) {
    return result ? result->get_header_value("Content-Type") : std::string("no answer");
  };
  EXPECT_EQ(typeOf(renderWith("*/*")), "image/png");
  EXPECT_EQ(typeOf(renderWith("application/json")), "application/json");
  EXPECT_EQ(typeOf(renderWith("image/png;q=0.1, application/json;q=0.9")), "application/json");
  EXPECT_EQ(typeOf(renderWith("application/json;q=0.5, image/*")), "image/png");
  EXPECT_EQ(typeOf(renderWith("application/*")), "application/json");
  EXPECT_EQ(typeOf(renderWith("application/json, image/png")), "application/json");  // order
  EXPECT_EQ(typeOf(renderWith("image/*;q=0, */*;q=0.1")), "application/json");
  EXPECT_EQ(typeOf(renderWith("text/html;q=oops, image/png")), "image/png");  // bad q: left out
  EXPECT_EQ(typeOf(http->Get("/v1/info", {{"Accept", "application/json;q=0.3, */*;q=0.1"}})),
            "application/json");
}

// The render thread counts a render just after its answer left: wait until the count stops moving.
double settledMetric(httplib::Client& http, const std::string& series) {
  double value = metricValue(http.Get("/metrics")->body, series);
  for (int i = 0; i < 50; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const double again = metricValue(http.Get("/metrics")->body, series);
    if (again == value) return value;
    value = again;
  }
  return value;
}

TEST_F(ConventionsTest, UnacceptableIs406BeforeAnyRender) {
  const std::string rendered = "lghd_renders_total{outcome=\"ok\"}";
  const double before = settledMetric(*http, rendered);
  const auto html = postJson(*http, "/v1/render", kSmall, {{"Accept", "text/html"}});
  const json error = expectError(html, 406, "not_acceptable");
  EXPECT_EQ(error["field"], "Accept");
  EXPECT_NE(error["message"].get<std::string>().find("image/png, application/json"),
            std::string::npos)
      << error.dump();
  const json exr = {{"output", {{"width", 16}, {"height", 8}, {"format", "exr"}}}};
  expectError(postJson(*http, "/v1/render", exr, {{"Accept", "image/png"}}), 406, "not_acceptable");
  expectError(postJson(*http, "/v1/render", kSmall, {{"Accept", "image/png;q=0"}}), 406,
              "not_acceptable");
  expectError(http->Get("/v1/info", {{"Accept", "image/png"}}), 406, "not_acceptable");
  expectError(http->Get("/metrics", {{"Accept", "application/json"}}), 406, "not_acceptable");
  const json zip = {{"assets", {"BoxTextured-glTF-Binary/BoxTextured.glb"}}, {"width", 16}};
  expectError(postJson(*http, "/v1/thumbnails", zip, {{"Accept", "application/x-ndjson"}}), 406,
              "not_acceptable");
  EXPECT_EQ(settledMetric(*http, rendered), before);
}

std::string runPromtool(const std::string& exposition) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("lghd-metrics-" + std::to_string(getpid()) + ".txt");
  std::ofstream(file) << exposition;
  const std::string command = "promtool check metrics < " + file.string() + " 2>&1; echo rc=$?";
  std::string output;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[512];
    while (fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
    pclose(pipe);
  }
  std::filesystem::remove(file);
  return output;
}

TEST_F(ConventionsTest, MetricsPassPromtoolAndCarryProcessMetrics) {
  // Traffic first, so that every kind of series is there: renders, a 406, a job.
  postJson(*http, "/v1/render", kSmall);
  http->Get("/v1/info", {{"Accept", "image/png"}});
  postJson(*http, "/v1/jobs", {{"kind", "render"}, {"request", kSmall}});
  waitForMetric(*http, "lghd_jobs_total{kind=\"render\",outcome=\"succeeded\"}", 1);
  const auto metrics = http->Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_EQ(metrics->get_header_value("Content-Type"), "text/plain; version=0.0.4; charset=utf-8");
  const std::string& text = metrics->body;

  ASSERT_EQ(std::system("command -v promtool >/dev/null"), 0)
      << "promtool is missing: scripts/install-deps installs it (Debian package prometheus)";
  EXPECT_EQ(runPromtool(text), "rc=0\n") << text;

  const double now = static_cast<double>(std::chrono::duration_cast<std::chrono::seconds>(
                                             std::chrono::system_clock::now().time_since_epoch())
                                             .count());
  const double start = metricValue(text, "process_start_time_seconds");
  EXPECT_LE(start, now + 1);
  EXPECT_GT(start, now - 3600);
  EXPECT_GT(metricValue(text, "process_resident_memory_bytes"), 1 << 20);
  EXPECT_GT(metricValue(text, "process_virtual_memory_bytes"),
            metricValue(text, "process_resident_memory_bytes"));
  EXPECT_GT(metricValue(text, "process_open_fds"), 2);
  EXPECT_GT(metricValue(text, "process_cpu_seconds_total"), 0);
  EXPECT_GE(metricValue(text, "process_threads"), 3);
  EXPECT_GE(metricValue(text,
                        "lghd_http_requests_total{route=\"/v1/info\",method=\"GET\","
                        "status=\"406\"}"),
            1);
}

// A daemon with CORS for one origin and a bearer token.
class CorsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    daemon = new DaemonProcess({"--cors-origin", "https://app.example, https://other.example"},
                               {"LGHD_AUTH_TOKEN=s3cret"});
  }
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
DaemonProcess* CorsTest::daemon = nullptr;

TEST_F(CorsTest, PreflightIsAnsweredBeforeAuthentication) {
  const auto preflight = http->Options(
      "/v1/jobs", {{"Origin", "https://app.example"},
                   {"Access-Control-Request-Method", "POST"},
                   {"Access-Control-Request-Headers", "authorization, content-type"}});
  ASSERT_TRUE(preflight);
  EXPECT_EQ(preflight->status, 204);
  EXPECT_EQ(preflight->get_header_value("Access-Control-Allow-Origin"), "https://app.example");
  EXPECT_EQ(preflight->get_header_value("Vary"), "Origin");
  EXPECT_EQ(preflight->get_header_value("Access-Control-Allow-Methods"), "POST, OPTIONS");
  const std::string allowed = preflight->get_header_value("Access-Control-Allow-Headers");
  EXPECT_NE(allowed.find("Authorization"), std::string::npos) << allowed;
  EXPECT_NE(allowed.find("Content-Type"), std::string::npos) << allowed;
  EXPECT_EQ(preflight->get_header_value("Access-Control-Max-Age"), "600");
}

TEST_F(CorsTest, AnswersFromAnAllowedOriginCarryTheHeadersErrorsIncluded) {
  const auto unauthorized = http->Get("/v1/info", {{"Origin", "https://other.example"}});
  expectError(unauthorized, 401, "unauthorized");
  EXPECT_EQ(unauthorized->get_header_value("Access-Control-Allow-Origin"), "https://other.example");

  const auto ok = http->Post(
      "/v1/render", {{"Origin", "https://app.example"}, {"Authorization", "Bearer s3cret"}},
      kSmall.dump(), "application/json");
  ASSERT_TRUE(ok);
  ASSERT_EQ(ok->status, 200) << ok->body;
  EXPECT_EQ(ok->get_header_value("Access-Control-Allow-Origin"), "https://app.example");
  const std::string exposed = ok->get_header_value("Access-Control-Expose-Headers");
  for (const char* header : {"X-Lgh-Timings", "Server-Timing", "Location", "X-Request-Id"}) {
    EXPECT_NE(exposed.find(header), std::string::npos) << header << " in " << exposed;
  }
}

TEST_F(CorsTest, OtherOriginsGetNoCorsHeaders) {
  const auto preflight = http->Options("/v1/render", {{"Origin", "https://evil.example"},
                                                      {"Access-Control-Request-Method", "POST"}});
  ASSERT_TRUE(preflight);
  EXPECT_FALSE(preflight->has_header("Access-Control-Allow-Origin"));
  EXPECT_FALSE(preflight->has_header("Access-Control-Allow-Methods"));
  const auto get = http->Get("/healthz", {{"Origin", "https://evil.example"}});
  ASSERT_TRUE(get);
  EXPECT_EQ(get->status, 200);
  EXPECT_FALSE(get->has_header("Access-Control-Allow-Origin"));
}

}  // namespace
}  // namespace lghd::test
