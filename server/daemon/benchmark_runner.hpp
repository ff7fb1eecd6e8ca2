// The benchmarks lghd runs for POST /v1/benchmark (docs/DAEMON.md, "Benchmarks"): one at a time,
// each in a child process (`lghd --run-benchmark BODY RENDERER`) that runs the very suite of
// `lgh-bench gi` with its own GL context and Vulkan device, prints progress lines on stderr and
// the JSON document on stdout. A child keeps the render thread free (a benchmark takes minutes),
// keeps a driver crash out of the daemon, and makes the document the CLI's own. Renders that run
// meanwhile share the GPU with it: their time is in its figures.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "lgh/renderer_options.hpp"

namespace lghd {

inline constexpr const char* kRunBenchmarkFlag = "--run-benchmark";

// The child's side: parses the body and the renderer options, runs the suite, prints the
// document (stdout) and "progress: ..." lines (stderr). Exit status 0, or 1 with
// {"error": {"code", "message"}} on stdout.
int runBenchmarkChild(const std::string& body, const std::string& renderer);

class BenchmarkRunner {
 public:
  explicit BenchmarkRunner(lgh::RendererOptions renderer);
  ~BenchmarkRunner();
  BenchmarkRunner(const BenchmarkRunner&) = delete;
  BenchmarkRunner& operator=(const BenchmarkRunner&) = delete;

  // Starts the benchmark of `body` (already checked by parseBenchmarkRequest) and returns its id.
  // Throws ApiError 429 with Retry-After while one runs, 503 when stopping or the child cannot
  // start.
  std::uint64_t start(const nlohmann::json& body);

  // {"id", "status": idle|running|done|failed, "request", "elapsed_s", "progress": {"steps",
  // "last", "lines"}, "error"}.
  nlohmann::json status() const;
  // The document of the last benchmark that finished; nullopt before any.
  std::optional<std::string> result() const;
  bool running() const;

  // Ends a running child (SIGTERM, then SIGKILL) and waits for it; refuses new ones after.
  void stop();

 private:
  void monitor(pid_t pid, int out, int err, std::uint64_t id);
  void finish(std::uint64_t id, int exitStatus, std::string output);

  lgh::RendererOptions renderer_;
  mutable std::mutex mutex_;
  enum class State { Idle, Running, Done, Failed };
  State state_ = State::Idle;
  bool stopping_ = false;
  std::uint64_t id_ = 0;
  nlohmann::json request_;
  std::chrono::steady_clock::time_point started_;
  std::chrono::steady_clock::time_point ended_;
  std::deque<std::string> lines_;  // the last progress lines
  std::size_t steps_ = 0;
  nlohmann::json error_;
  std::optional<std::string> result_;
  std::atomic<pid_t> child_ = 0;
  std::thread thread_;
};

}  // namespace lghd
