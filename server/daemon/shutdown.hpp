// Waits for SIGTERM/SIGINT (or a fatal error reported from inside) on its own thread and then
// runs the shutdown sequence once. The signals are blocked in every thread and taken with
// sigtimedwait, so no work happens in a signal handler.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <thread>

namespace lghd {

class ShutdownSupervisor {
 public:
  // Call before any other thread starts: threads inherit the signal mask.
  static void blockSignals();

  ~ShutdownSupervisor();

  // Starts waiting; `sequence` runs once on the supervisor thread when a stop is due.
  void start(std::function<void()> sequence);
  // A stop from inside the process (the renderer cannot run), exiting with `exitCode`.
  void requestStop(int exitCode, const std::string& reason);
  void join();
  int exitCode() const { return exitCode_; }

 private:
  void run();

  std::function<void()> sequence_;
  std::atomic<bool> stopRequested_{false};
  std::atomic<int> exitCode_{0};
  std::thread thread_;
};

}  // namespace lghd
