// A watchdog for the render thread. A GL call that never returns (a hung GPU or driver) cannot be
// interrupted from another thread, and a context stuck in one cannot be torn down; the only
// recovery is a new process. The render thread arms the watchdog with the time past which its
// current work counts as hung and disarms it when the work is done; past that time the watchdog
// calls its handler, once, on its own thread.
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "clock.hpp"

namespace lghd {

class RenderWatchdog {
 public:
  using Handler = std::function<void()>;

  explicit RenderWatchdog(Handler onHung);
  ~RenderWatchdog();
  RenderWatchdog(const RenderWatchdog&) = delete;
  RenderWatchdog& operator=(const RenderWatchdog&) = delete;

  void arm(Clock::time_point hungAfter);
  void disarm();
  bool fired() const;

 private:
  void run();

  Handler onHung_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<Clock::time_point> hungAfter_;
  bool stopping_ = false;
  bool fired_ = false;
  std::thread thread_;
};

// Keeps `watchdog` (none: no watchdog) armed for one piece of GL work, disarmed however it ends.
class WatchdogScope {
 public:
  WatchdogScope(RenderWatchdog* watchdog, Clock::time_point hungAfter) : watchdog_(watchdog) {
    if (watchdog_ != nullptr) watchdog_->arm(hungAfter);
  }
  ~WatchdogScope() {
    if (watchdog_ != nullptr) watchdog_->disarm();
  }
  WatchdogScope(const WatchdogScope&) = delete;
  WatchdogScope& operator=(const WatchdogScope&) = delete;

 private:
  RenderWatchdog* watchdog_;
};

}  // namespace lghd
