// Load on the real daemon: many clients at once get results or 429s, never another 5xx; SIGTERM
// under load exits 0 and leaves no request hanging.
#include <gtest/gtest.h>

#include <signal.h>

#include <atomic>
#include <mutex>
#include <thread>

#include "daemon_process.hpp"
#include "http_helpers.hpp"

namespace lghd::test {
namespace {

using Clock = std::chrono::steady_clock;

const json kSmall = {{"output", {{"width", 32}, {"height", 32}}}};

struct Tally {
  std::mutex mutex;
  std::map<int, int> statuses;          // HTTP status -> count
  std::map<std::string, int> failures;  // transport error -> count
  bool retryAfterOnEvery429 = true;
  Clock::duration slowestFailure{};

  void add(const httplib::Result& result, Clock::duration took = {}) {
    std::lock_guard lock(mutex);
    if (!result) {
      ++failures[httplib::to_string(result.error())];
      slowestFailure = std::max(slowestFailure, took);
      return;
    }
    ++statuses[result->status];
    if (result->status == 429 && result->get_header_value("Retry-After").empty()) {
      retryAfterOnEvery429 = false;
    }
  }
  std::string describe() {
    std::string text;
    for (const auto& [status, count] : statuses) {
      text += std::to_string(status) + "x" + std::to_string(count) + " ";
    }
    for (const auto& [error, count] : failures) text += error + "x" + std::to_string(count) + " ";
    return text;
  }
};

TEST(ConcurrencyTest, ManyClientsGetResultsOr429sNeverOther5xx) {
  DaemonProcess daemon({"--queue-depth", "2", "--test-render-delay-ms", "40"});
  Tally tally;
  std::vector<std::thread> clients;
  clients.reserve(clients.size() + 24);
  for (int i = 0; i < 24; ++i) {
    clients.emplace_back([&] {
      auto http = daemon.client();
      for (int round = 0; round < 2; ++round) tally.add(postJson(*http, "/v1/render", kSmall));
    });
  }
  for (auto& client : clients) client.join();
  std::cerr << "answers: " << tally.describe() << "\n";
  EXPECT_TRUE(tally.failures.empty());
  for (const auto& [status, count] : tally.statuses) {
    EXPECT_TRUE(status == 200 || status == 429) << status;
  }
  EXPECT_GT(tally.statuses[200], 0);
  EXPECT_GT(tally.statuses[429], 0) << "24 clients against a queue of 2 should see 429s";
  EXPECT_TRUE(tally.retryAfterOnEvery429);

  auto http = daemon.client();
  EXPECT_EQ(http->Get("/healthz")->status, 200);
  const auto after = postJson(*http, "/v1/render", kSmall);
  ASSERT_TRUE(after);
  EXPECT_EQ(after->status, 200);
  const std::string series =
      "lghd_http_requests_total{route=\"/v1/render\",method=\"POST\",status=\"429\"}";
  EXPECT_EQ(waitForMetric(*http, series, tally.statuses[429]), tally.statuses[429]);
  if (HasFailure()) std::cerr << daemon.log();
}

TEST(ConcurrencyTest, SigtermDuringLoadExitsZeroAndAnswersEveryRequest) {
  DaemonProcess daemon(
      {"--queue-depth", "4", "--test-render-delay-ms", "100", "--grace-seconds", "5"});
  Tally tally;
  std::atomic<bool> stopping = false;
  std::atomic<int> finishedClients = 0;
  std::vector<std::thread> clients;
  clients.reserve(clients.size() + 8);
  for (int i = 0; i < 8; ++i) {
    clients.emplace_back([&] {
      // Until the daemon stops taking connections: each request on a fresh connection.
      for (int round = 0; round < 200; ++round) {
        auto http = daemon.client(std::chrono::seconds(20));
        const auto start = Clock::now();
        const auto result = postJson(*http, "/v1/render", kSmall);
        tally.add(result, Clock::now() - start);
        if (stopping && !result) break;
      }
      ++finishedClients;
    });
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  stopping = true;
  const auto signalled = Clock::now();
  const std::optional<int> status = daemon.stop(SIGTERM, std::chrono::seconds(20));
  const auto exitTime = Clock::now() - signalled;
  for (auto& client : clients) client.join();
  std::cerr << "answers: " << tally.describe() << "\n";
  ASSERT_TRUE(status.has_value()) << "lghd did not exit after SIGTERM\n" << daemon.log();
  EXPECT_EQ(*status, 0) << daemon.log();
  EXPECT_LT(exitTime, std::chrono::seconds(8));
  EXPECT_EQ(finishedClients, 8);
  EXPECT_GT(tally.statuses[200], 0);
  for (const auto& [code, count] : tally.statuses) {
    EXPECT_TRUE(code == 200 || code == 429 || code == 503) << code;
  }
  // After the listener closed, new connections are refused (Connection), or, for one that the
  // kernel had queued but lghd never accepted, reset (Read). Neither may be a hang.
  for (const auto& [error, count] : tally.failures) {
    EXPECT_TRUE(error == httplib::to_string(httplib::Error::Connection) ||
                error == httplib::to_string(httplib::Error::Read))
        << error;
  }
  EXPECT_LT(tally.slowestFailure, std::chrono::seconds(3));
  EXPECT_NE(daemon.log().find("\"event\":\"drained\""), std::string::npos);
}

TEST(ConcurrencyTest, GracePeriodOverCancelsQueuedRendersWith503) {
  DaemonProcess daemon(
      {"--queue-depth", "8", "--test-render-delay-ms", "400", "--grace-seconds", "0.3"});
  Tally tally;
  std::vector<std::thread> clients;
  clients.reserve(clients.size() + 5);
  for (int i = 0; i < 5; ++i) {
    clients.emplace_back([&] {
      auto http = daemon.client(std::chrono::seconds(20));
      tally.add(postJson(*http, "/v1/render", kSmall));
    });
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const std::optional<int> status = daemon.stop(SIGTERM, std::chrono::seconds(15));
  for (auto& client : clients) client.join();
  std::cerr << "answers: " << tally.describe() << "\n";
  ASSERT_TRUE(status.has_value()) << daemon.log();
  EXPECT_EQ(*status, 0);
  EXPECT_TRUE(tally.failures.empty());
  EXPECT_GT(tally.statuses[503], 0) << "5 renders of 400 ms cannot all finish in 0.3 s";
  EXPECT_EQ(tally.statuses[200] + tally.statuses[503], 5) << daemon.log();
}

}  // namespace
}  // namespace lghd::test
