// POST /v1/jobs against the real daemon: 202 + Location, status with progress and ETA, the
// result of each kind (render, thumbnails, benchmark), cancellation, the bounds (count, memory,
// TTL, batch), submission errors naming the field, and the metrics. Status and result bodies are
// checked against their proto schemas.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "daemon_process.hpp"
#include "http_helpers.hpp"
#include "lgh/request.hpp"

namespace lghd::test {
namespace {

using namespace std::chrono_literals;

const std::string kBox = "BoxTextured-glTF-Binary/BoxTextured.glb";

void expectMatchesSchema(const json& value, const std::string& schemaFile) {
  try {
    lgh::validateAgainstProtoSchema(value, schemaFile);
  } catch (const lgh::Error& error) {
    ADD_FAILURE() << schemaFile << ": " << error.field() << ": " << error.what() << "\n"
                  << value.dump(2);
  }
}

// POSTs the job and checks the 202; returns its status.
json submit(httplib::Client& http, const json& job) {
  const auto result = postJson(http, "/v1/jobs", job);
  if (!result) {
    ADD_FAILURE() << "no answer";
    return {};
  }
  EXPECT_EQ(result->status, 202) << result->body;
  json status = json::parse(result->body);
  EXPECT_EQ(result->get_header_value("Location"), "/v1/jobs/" + status.value("id", ""));
  expectMatchesSchema(status, "job-status.schema.json");
  return status;
}

json jobStatus(httplib::Client& http, const std::string& id) {
  const auto result = http.Get(("/v1/jobs/" + id).c_str());
  if (!result || result->status != 200) {
    ADD_FAILURE() << "GET /v1/jobs/" << id << ": " << (result ? result->body : "no answer");
    return {};
  }
  json status = json::parse(result->body);
  expectMatchesSchema(status, "job-status.schema.json");
  return status;
}

bool finished(const json& status) {
  const std::string state = status.value("status", "");
  return state != "queued" && state != "running";
}

json waitForJob(httplib::Client& http, const std::string& id) {
  const auto end = std::chrono::steady_clock::now() + 120s;
  json status;
  do {
    status = jobStatus(http, id);
    if (finished(status)) return status;
    std::this_thread::sleep_for(20ms);
  } while (std::chrono::steady_clock::now() < end);
  ADD_FAILURE() << "job " << id << " did not finish: " << status.dump();
  return status;
}

class JobsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    daemon = new DaemonProcess({"--max-job-batch", "6", "--jobs-memory-mb", "2", "--max-jobs", "16",
                                "--job-ttl-seconds", "2"});
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
DaemonProcess* JobsTest::daemon = nullptr;

TEST_F(JobsTest, RenderJobIsAnsweredLikeARender) {
  const json job = {
      {"kind", "render"},
      {"request", {{"scene", {{"asset", kBox}}}, {"output", {{"width", 64}, {"height", 48}}}}}};
  const json queued = submit(*http, job);
  EXPECT_EQ(queued["kind"], "render");
  EXPECT_EQ(queued["progress"]["total"], 1);
  const json done = waitForJob(*http, queued["id"]);
  ASSERT_EQ(done["status"], "succeeded") << done.dump();
  EXPECT_EQ(done["progress"]["done"], 1);
  EXPECT_EQ(done["progress"]["fraction"], 1.0);
  EXPECT_FALSE(done["finished_at"].is_null());
  EXPECT_FALSE(done["expires_at"].is_null());
  EXPECT_EQ(done["result"]["mime"], "image/png");

  const std::string href = done["result"]["href"];
  const auto image = http->Get(href.c_str());
  ASSERT_TRUE(image);
  ASSERT_EQ(image->status, 200) << image->body;
  EXPECT_EQ(image->get_header_value("Content-Type"), "image/png");
  EXPECT_FALSE(image->get_header_value("X-Lgh-Timings").empty());
  EXPECT_EQ(image->body.size(), done["result"]["bytes"].get<std::size_t>());
  const auto decoded = decodeBody(image->body);
  EXPECT_EQ(decoded.width, 64);
  EXPECT_EQ(decoded.height, 48);

  const auto asJson = http->Get(href.c_str(), {{"Accept", "application/json"}});
  ASSERT_TRUE(asJson);
  ASSERT_EQ(asJson->status, 200);
  const json answer = json::parse(asJson->body);
  expectMatchesSchema(answer, "render-response.schema.json");
  EXPECT_EQ(answer["width"], 64);
}

TEST_F(JobsTest, ThumbnailsJobIsTheZipWithTheErrorsOfBadAssets) {
  const json job = {
      {"kind", "thumbnails"},
      {"request",
       {{"assets", {kBox, "missing/Nothing.glb", "BoxTextured-glTF/BoxTextured.gltf"}},
        {"width", 32},
        {"height", 32},
        {"name_template", "{index}.png"}}}};
  const json done = waitForJob(*http, submit(*http, job)["id"]);
  ASSERT_EQ(done["status"], "succeeded") << done.dump();
  EXPECT_EQ(done["progress"]["total"], 3);
  EXPECT_EQ(done["progress"]["failed"], 1);
  const auto zip = http->Get(done["result"]["href"].get<std::string>().c_str());
  ASSERT_TRUE(zip);
  ASSERT_EQ(zip->status, 200);
  EXPECT_EQ(zip->get_header_value("Content-Type"), "application/zip");
  EXPECT_EQ(zip->get_header_value("X-Lgh-Thumbnails-Ok"), "2");
  EXPECT_EQ(zip->get_header_value("X-Lgh-Thumbnails-Failed"), "1");
  const auto members = unzip(zip->body);
  ASSERT_TRUE(members.contains("0.png") && members.contains("2.png") &&
              members.contains("errors.json"));
  const auto comments = zipComments(zip->body);
  EXPECT_EQ(comments.at("0.png"), R"({"gpu":0})") << "each thumbnail names its GPU";
  EXPECT_EQ(comments.at("errors.json"), "");
  const json errors = json::parse(members.at("errors.json"));
  ASSERT_EQ(errors.size(), 1U);
  EXPECT_EQ(errors[0]["error"]["code"], "not_found");
  EXPECT_EQ(errors[0]["error"]["field"], "/assets/1");
}

TEST_F(JobsTest, BenchmarkJobGivesPerPassMedians) {
  const json job = {{"kind", "benchmark"},
                    {"request", {{"output", {{"width", 32}, {"height", 32}}}}},
                    {"warmup", 1},
                    {"iterations", 3}};
  const json done = waitForJob(*http, submit(*http, job)["id"]);
  ASSERT_EQ(done["status"], "succeeded") << done.dump();
  EXPECT_EQ(done["progress"]["total"], 4);
  EXPECT_EQ(done["result"]["mime"], "application/json");
  const auto result = http->Get(done["result"]["href"].get<std::string>().c_str());
  ASSERT_TRUE(result);
  const json benchmark = json::parse(result->body);
  expectMatchesSchema(benchmark, "benchmark-result.schema.json");
  EXPECT_EQ(benchmark["total_ms"].size(), 3U);
  EXPECT_EQ(benchmark["gpus"], json::array({0, 0, 0}));
  EXPECT_EQ(benchmark["scene_cache_hits"], 3);  // the warmup render loaded the scene
  bool hasTotal = false;
  for (const json& row : benchmark["timings"]) hasTotal |= row["pass"] == "total";
  EXPECT_TRUE(hasTotal) << benchmark["timings"].dump();
}

TEST_F(JobsTest, AFailedRenderJobAnswersItsError) {
  const json job = {{"kind", "render"}, {"request", {{"scene", {{"asset", "missing.glb"}}}}}};
  const json done = waitForJob(*http, submit(*http, job)["id"]);
  ASSERT_EQ(done["status"], "failed");
  EXPECT_EQ(done["error"]["code"], "not_found");
  EXPECT_EQ(done["error"]["field"], "/scene/asset");
  EXPECT_TRUE(done["result"].is_null());
  expectError(http->Get(("/v1/jobs/" + done["id"].get<std::string>() + "/result").c_str()), 404,
              "not_found");
}

TEST_F(JobsTest, SubmissionErrorsNameTheField) {
  EXPECT_EQ(
      expectError(postJson(*http, "/v1/jobs", {{"kind", "bake"}}), 400, "bad_request")["field"],
      "/kind");
  EXPECT_EQ(expectError(postJson(*http, "/v1/jobs", json::object()), 400, "bad_request")["field"],
            "/kind");
  EXPECT_EQ(expectError(postJson(*http, "/v1/jobs",
                                 {{"kind", "render"}, {"request", {{"output", {{"width", 0}}}}}}),
                        422, "invalid")["field"],
            "/request/output/width");
  EXPECT_EQ(
      expectError(postJson(*http, "/v1/jobs",
                           {{"kind", "render"}, {"request", {{"output", {{"width", 5000}}}}}}),
                  413, "too_large")["field"],
      "/request/output/width");
  EXPECT_EQ(expectError(postJson(*http, "/v1/jobs",
                                 {{"kind", "thumbnails"},
                                  {"request", {{"assets", {kBox}}, {"format", "ndjson"}}}}),
                        400, "bad_request")["field"],
            "/request/format");
  // --max-job-batch 6: seven thumbnails, or a benchmark of 1 + 6 renders, are too many.
  EXPECT_EQ(expectError(postJson(*http, "/v1/jobs",
                                 {{"kind", "thumbnails"},
                                  {"request", {{"assets", std::vector<std::string>(7, kBox)}}}}),
                        413, "too_large")["field"],
            "/request/assets");
  EXPECT_EQ(expectError(postJson(*http, "/v1/jobs", {{"kind", "benchmark"}, {"iterations", 6}}),
                        413, "too_large")["field"],
            "/iterations");
  // --jobs-memory-mb 2: a 1024x1024 PNG may take 4 MiB.
  EXPECT_EQ(expectError(postJson(*http, "/v1/jobs",
                                 {{"kind", "render"},
                                  {"request", {{"output", {{"width", 1024}, {"height", 1024}}}}}}),
                        413, "too_large")["field"],
            "/request");
  const auto multipart = http->Post("/v1/jobs", httplib::MultipartFormDataItems{requestPart({})});
  EXPECT_EQ(expectError(multipart, 400, "bad_request")["field"], "Content-Type");
  expectError(http->Post("/v1/jobs", "{\"kind\": ", "application/json"), 400, "bad_request");
}

TEST_F(JobsTest, UnknownJobsAreNotFound) {
  const std::string unknown = "/v1/jobs/0123456789abcdef0123456789abcdef";
  EXPECT_EQ(expectError(http->Get(unknown.c_str()), 404, "not_found")["field"], "id");
  expectError(http->Get((unknown + "/result").c_str()), 404, "not_found");
  expectError(http->Delete(unknown.c_str()), 404, "not_found");
  expectError(http->Get("/v1/jobs/not-an-id"), 404, "not_found");
}

TEST_F(JobsTest, FinishedJobsExpireAfterTheirTtl) {
  const std::string id = submit(
      *http, {{"kind", "render"}, {"request", {{"output", {{"width", 8}, {"height", 8}}}}}})["id"];
  ASSERT_EQ(waitForJob(*http, id)["status"], "succeeded");
  std::this_thread::sleep_for(2500ms);  // --job-ttl-seconds 2
  expectError(http->Get(("/v1/jobs/" + id).c_str()), 404, "not_found");
}

TEST_F(JobsTest, DeleteForgetsAFinishedJob) {
  const std::string id = submit(
      *http, {{"kind", "render"}, {"request", {{"output", {{"width", 8}, {"height", 8}}}}}})["id"];
  ASSERT_EQ(waitForJob(*http, id)["status"], "succeeded");
  const auto deleted = http->Delete(("/v1/jobs/" + id).c_str());
  ASSERT_TRUE(deleted);
  EXPECT_EQ(deleted->status, 200);
  EXPECT_EQ(json::parse(deleted->body)["status"], "succeeded");
  expectError(http->Get(("/v1/jobs/" + id).c_str()), 404, "not_found");
}

TEST_F(JobsTest, JobsAreCountedInTheMetrics) {
  const std::string id = submit(
      *http, {{"kind", "render"}, {"request", {{"output", {{"width", 8}, {"height", 8}}}}}})["id"];
  ASSERT_EQ(waitForJob(*http, id)["status"], "succeeded");
  EXPECT_GE(waitForMetric(*http, "lghd_jobs_total{kind=\"render\",outcome=\"succeeded\"}", 1), 1);
  const std::string text = http->Get("/metrics")->body;
  EXPECT_EQ(metricValue(text, "lghd_jobs_capacity"), 16);
  EXPECT_EQ(metricValue(text, "lghd_jobs_memory_budget_bytes"), 2 << 20);
  EXPECT_GE(metricValue(text, "lghd_jobs{status=\"succeeded\"}"), 1);
  EXPECT_GE(metricValue(text,
                        "lghd_http_requests_total{route=\"/v1/jobs/{id}\",method=\"GET\","
                        "status=\"200\"}"),
            1);
  EXPECT_GE(metricValue(text, "lghd_renders_total{outcome=\"ok\"}"), 1);
}

// A daemon whose renders take 300 ms each: jobs are seen queued and running.
class SlowJobsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    daemon = new DaemonProcess({"--test-render-delay-ms", "300", "--max-jobs", "3"});
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
DaemonProcess* SlowJobsTest::daemon = nullptr;

json fourThumbnails() {
  return {
      {"kind", "thumbnails"},
      {"request", {{"assets", std::vector<std::string>(4, kBox)}, {"width", 16}, {"height", 16}}}};
}

TEST_F(SlowJobsTest, ProgressEtaConflictCancelAndTheCountLimit) {
  const std::string running = submit(*http, fourThumbnails())["id"];
  const std::string queued = submit(*http, fourThumbnails())["id"];
  const std::string third = submit(*http, fourThumbnails())["id"];
  // --max-jobs 3: a fourth is refused until one is deleted or expires.
  const auto full = postJson(*http, "/v1/jobs", fourThumbnails());
  expectError(full, 429, "queue_full");
  EXPECT_GE(std::stoi(full->get_header_value("Retry-After")), 1);

  // Running, with progress and an ETA once a render has been timed.
  json status;
  const auto end = std::chrono::steady_clock::now() + 60s;
  do {
    status = jobStatus(*http, running);
    std::this_thread::sleep_for(20ms);
  } while (status["progress"]["done"] < 1 && std::chrono::steady_clock::now() < end);
  EXPECT_EQ(status["status"], "running") << status.dump();
  EXPECT_GE(status["progress"]["done"], 1);
  ASSERT_TRUE(status["eta_seconds"].is_number()) << status.dump();
  EXPECT_GT(status["eta_seconds"].get<double>(), 0.0);
  const json waiting = jobStatus(*http, queued);
  EXPECT_EQ(waiting["status"], "queued");
  ASSERT_TRUE(waiting["eta_seconds"].is_number()) << waiting.dump();
  EXPECT_GT(waiting["eta_seconds"].get<double>(), status["eta_seconds"].get<double>());

  // Not ready yet: 409 with Retry-After.
  const auto early = http->Get(("/v1/jobs/" + queued + "/result").c_str());
  EXPECT_EQ(expectError(early, 409, "conflict")["field"], "id");
  EXPECT_GE(std::stoi(early->get_header_value("Retry-After")), 1);

  // Cancel the queued one (at once) and the running one (after its render in progress).
  const auto cancelQueued = http->Delete(("/v1/jobs/" + queued).c_str());
  ASSERT_TRUE(cancelQueued);
  EXPECT_EQ(json::parse(cancelQueued->body)["status"], "cancelled");
  const auto cancelRunning = http->Delete(("/v1/jobs/" + running).c_str());
  ASSERT_TRUE(cancelRunning);
  EXPECT_EQ(json::parse(cancelRunning->body)["status"], "cancelled");
  expectError(http->Get(("/v1/jobs/" + queued + "/result").c_str()), 409, "conflict");
  const json cancelled = jobStatus(*http, running);
  EXPECT_EQ(cancelled["status"], "cancelled");
  EXPECT_LT(cancelled["progress"]["done"], 4);

  // The third runs once the cancelled one lets go; the cancelled jobs' renders are not made.
  const json third_done = waitForJob(*http, third);
  EXPECT_EQ(third_done["status"], "succeeded");
  EXPECT_EQ(jobStatus(*http, running)["progress"]["done"], cancelled["progress"]["done"]);
  EXPECT_GE(waitForMetric(*http, "lghd_jobs_total{kind=\"thumbnails\",outcome=\"cancelled\"}", 2),
            2);
}

}  // namespace
}  // namespace lghd::test
