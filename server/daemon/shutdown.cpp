#include "shutdown.hpp"

#include <csignal>
#include <ctime>

#include "lgh/thread_name.hpp"
#include "logging.hpp"

namespace lghd {
namespace {

sigset_t shutdownSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  return signals;
}

}  // namespace

void ShutdownSupervisor::blockSignals() {
  const sigset_t signals = shutdownSignals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::signal(SIGPIPE, SIG_IGN);  // a client hanging up must not kill the daemon
}

ShutdownSupervisor::~ShutdownSupervisor() {
  if (thread_.joinable()) {
    stopRequested_ = true;
    thread_.join();
  }
}

void ShutdownSupervisor::start(std::function<void()> sequence) {
  sequence_ = std::move(sequence);
  thread_ = std::thread([this] { run(); });
}

void ShutdownSupervisor::requestStop(int exitCode, const std::string& reason) {
  if (stopRequested_.exchange(true)) return;
  exitCode_ = exitCode;
  logging::event(spdlog::level::warn, "shutdown_requested",
                 {{"reason", reason}, {"exit_code", exitCode}});
}

void ShutdownSupervisor::join() {
  if (thread_.joinable()) thread_.join();
}

void ShutdownSupervisor::run() {
  lgh::nameThisThread("lgh-shutdown");
  const sigset_t signals = shutdownSignals();
  const timespec poll{0, 100'000'000};
  while (!stopRequested_) {
    siginfo_t info{};
    const int signal = sigtimedwait(&signals, &info, &poll);
    if (signal > 0 && !stopRequested_.exchange(true)) {
      logging::event(spdlog::level::info, "signal",
                     {{"signal", signal == SIGTERM ? "SIGTERM" : "SIGINT"}});
    }
  }
  if (sequence_) sequence_();
}

}  // namespace lghd
