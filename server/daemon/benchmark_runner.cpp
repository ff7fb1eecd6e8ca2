#include "benchmark_runner.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <iostream>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "api_error.hpp"
#include "benchmark_request.hpp"
#include "lgh/bench/gi_benchmark.hpp"
#include "lgh/error.hpp"
#include "lgh/thread_name.hpp"
#include "logging.hpp"

extern char** environ;

namespace lghd {
namespace {

using json = nlohmann::json;

constexpr std::size_t kKeptLines = 20;
constexpr const char* kProgressPrefix = "progress: ";
constexpr int kRetryAfterSeconds = 60;
constexpr auto kTermGrace = std::chrono::seconds(2);

const char* stateName(int state) {
  static constexpr std::array<const char*, 4> kNames{"idle", "running", "done", "failed"};
  return kNames.at(static_cast<std::size_t>(state));
}

void closeFd(int& fd) {
  if (fd >= 0) close(fd);
  fd = -1;
}

std::string exitText(int status) {
  if (WIFEXITED(status)) return fmt::format("exit status {}", WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return fmt::format("signal {}", WTERMSIG(status));
  return "unknown status";
}

}  // namespace

int runBenchmarkChild(const std::string& body, const std::string& renderer) {
  spdlog::set_level(spdlog::level::off);  // stderr carries the progress lines alone
  try {
    // The daemon checked the body against its limits already.
    lgh::RequestLimits unlimited;
    unlimited.maxWidth = unlimited.maxHeight = 1 << 16;
    unlimited.maxVpls = 1 << 30;
    lgh::bench::GiBenchmarkOptions options = parseBenchmarkRequest(json::parse(body), unlimited);
    options.renderer = rendererOptionsFromJson(json::parse(renderer));
    options.progress = [](const std::string& line) {
      std::cerr << kProgressPrefix << line << std::endl;
    };
    const lgh::bench::GiBenchmarkResult result = lgh::bench::runGiBenchmark(options);
    std::cout << lgh::bench::giBenchmarkJson(result).dump(2) << std::endl;
    return 0;
  } catch (const lgh::Error& error) {
    std::cout << json{{"error",
                       {{"code", lgh::errorCodeName(error.code())}, {"message", error.what()}}}}
                     .dump()
              << std::endl;
  } catch (const std::exception& error) {
    std::cout << json{{"error", {{"code", "internal"}, {"message", error.what()}}}}.dump()
              << std::endl;
  }
  return 1;
}

BenchmarkRunner::BenchmarkRunner(lgh::RendererOptions renderer) : renderer_(std::move(renderer)) {}

BenchmarkRunner::~BenchmarkRunner() { stop(); }

bool BenchmarkRunner::running() const {
  const std::lock_guard lock(mutex_);
  return state_ == State::Running;
}

std::uint64_t BenchmarkRunner::start(const nlohmann::json& body) {
  std::unique_lock lock(mutex_);
  if (stopping_) throw unavailable("the daemon is shutting down");
  if (state_ == State::Running) {
    throw queueFull(fmt::format("benchmark {} is still running: one at a time (GET "
                                "/v1/benchmark shows its progress)",
                                id_),
                    kRetryAfterSeconds);
  }
  if (thread_.joinable()) thread_.join();  // the last one's monitor has finished
  std::array<int, 2> out{-1, -1};
  std::array<int, 2> err{-1, -1};
  if (pipe2(out.data(), O_CLOEXEC) != 0 || pipe2(err.data(), O_CLOEXEC) != 0) {
    for (int* fd : {&out[0], &out[1], &err[0], &err[1]}) closeFd(*fd);
    throw unavailable(fmt::format("cannot start the benchmark: pipe: {}", std::strerror(errno)));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err[1], STDERR_FILENO);
  // lghd blocks SIGTERM/SIGINT in every thread for its shutdown supervisor; the child must not
  // inherit that mask.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  std::string self = "/proc/self/exe";
  std::string flag = kRunBenchmarkFlag;
  std::string bodyText = body.dump();
  std::string rendererText = rendererOptionsJson(renderer_).dump();
  std::array<char*, 5> argv{self.data(), flag.data(), bodyText.data(), rendererText.data(),
                            nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, self.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  closeFd(out[1]);
  closeFd(err[1]);
  if (spawned != 0) {
    closeFd(out[0]);
    closeFd(err[0]);
    throw unavailable(
        fmt::format("cannot start the benchmark process: {}", std::strerror(spawned)));
  }
  child_ = pid;
  state_ = State::Running;
  request_ = body;
  started_ = std::chrono::steady_clock::now();
  lines_.clear();
  steps_ = 0;
  error_ = nullptr;
  const std::uint64_t id = ++id_;
  thread_ = std::thread(
      [this, pid, outFd = out[0], errFd = err[0], id] { monitor(pid, outFd, errFd, id); });
  logging::event(spdlog::level::info, "benchmark_started",
                 {{"id", id}, {"pid", pid}, {"request", body}});
  return id;
}

void BenchmarkRunner::monitor(pid_t pid, int out, int err, std::uint64_t id) {
  lgh::nameThisThread("lgh-benchmark");
  std::string output;
  std::string pending;
  std::array<char, 4096> buffer{};
  std::array<pollfd, 2> fds{{{out, POLLIN, 0}, {err, POLLIN, 0}}};
  while (fds[0].fd >= 0 || fds[1].fd >= 0) {
    if (poll(fds.data(), fds.size(), -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (std::size_t i = 0; i < fds.size(); ++i) {
      if (fds[i].fd < 0 || fds[i].revents == 0) continue;
      const ssize_t count = read(fds[i].fd, buffer.data(), buffer.size());
      if (count <= 0) {
        if (count < 0 && errno == EINTR) continue;
        close(fds[i].fd);
        fds[i].fd = -1;
        continue;
      }
      if (i == 0) {
        output.append(buffer.data(), static_cast<std::size_t>(count));
        continue;
      }
      pending.append(buffer.data(), static_cast<std::size_t>(count));
      for (std::size_t end = pending.find('\n'); end != std::string::npos;
           end = pending.find('\n')) {
        std::string line = pending.substr(0, end);
        pending.erase(0, end + 1);
        if (line.rfind(kProgressPrefix, 0) == 0) line.erase(0, std::strlen(kProgressPrefix));
        const std::lock_guard lock(mutex_);
        ++steps_;
        lines_.push_back(std::move(line));
        if (lines_.size() > kKeptLines) lines_.pop_front();
      }
    }
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  child_ = 0;
  finish(id, status, std::move(output));
}

void BenchmarkRunner::finish(std::uint64_t id, int exitStatus, std::string output) {
  const std::lock_guard lock(mutex_);
  ended_ = std::chrono::steady_clock::now();
  const bool ok = WIFEXITED(exitStatus) && WEXITSTATUS(exitStatus) == 0;
  json document;
  try {
    document = json::parse(output);
  } catch (const std::exception&) {
    document = nullptr;
  }
  if (ok && document.is_object() && !document.contains("error")) {
    state_ = State::Done;
    result_ = std::move(output);
  } else {
    state_ = State::Failed;
    error_ = document.is_object() && document.contains("error")
                 ? document.at("error")
                 : json{{"code", "internal"},
                        {"message", "the benchmark process failed (" + exitText(exitStatus) + ")"}};
  }
  logging::event(ok ? spdlog::level::info : spdlog::level::err, "benchmark_finished",
                 {{"id", id},
                  {"status", stateName(static_cast<int>(state_))},
                  {"seconds", std::chrono::duration<double>(ended_ - started_).count()}});
}

nlohmann::json BenchmarkRunner::status() const {
  const std::lock_guard lock(mutex_);
  json body = {{"id", id_}, {"status", stateName(static_cast<int>(state_))}};
  if (state_ == State::Idle) return body;
  const auto end = state_ == State::Running ? std::chrono::steady_clock::now() : ended_;
  body["request"] = request_;
  body["elapsed_s"] = std::chrono::duration<double>(end - started_).count();
  body["progress"] = {{"steps", steps_},
                      {"last", lines_.empty() ? json(nullptr) : json(lines_.back())},
                      {"lines", std::vector<std::string>(lines_.begin(), lines_.end())}};
  if (state_ == State::Failed) body["error"] = error_;
  if (state_ == State::Done) body["result"] = "/v1/benchmark/result";
  return body;
}

std::optional<std::string> BenchmarkRunner::result() const {
  const std::lock_guard lock(mutex_);
  return result_;
}

void BenchmarkRunner::stop() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  if (const pid_t pid = child_; pid > 0) {
    kill(pid, SIGTERM);
    const auto deadline = std::chrono::steady_clock::now() + kTermGrace;
    while (child_ != 0 && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (const pid_t left = child_; left > 0) kill(left, SIGKILL);
  }
  if (thread_.joinable()) thread_.join();
}

}  // namespace lghd
