#include "render_watchdog.hpp"

#include <utility>

#include "lgh/thread_name.hpp"

namespace lghd {

RenderWatchdog::RenderWatchdog(Handler onHung) : onHung_(std::move(onHung)) {
  thread_ = std::thread([this] { run(); });
}

RenderWatchdog::~RenderWatchdog() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void RenderWatchdog::arm(Clock::time_point hungAfter) {
  {
    std::lock_guard lock(mutex_);
    hungAfter_ = hungAfter;
  }
  changed_.notify_all();
}

void RenderWatchdog::disarm() {
  {
    std::lock_guard lock(mutex_);
    hungAfter_.reset();
  }
  changed_.notify_all();
}

bool RenderWatchdog::fired() const {
  std::lock_guard lock(mutex_);
  return fired_;
}

void RenderWatchdog::run() {
  lgh::nameThisThread("lgh-watchdog");
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    if (!hungAfter_) {
      changed_.wait(lock);
      continue;
    }
    const Clock::time_point hungAfter = *hungAfter_;
    // Woken early by arm/disarm/stop: look again at what is armed now.
    if (changed_.wait_until(lock, hungAfter) == std::cv_status::no_timeout) continue;
    if (stopping_ || hungAfter_ != hungAfter) continue;
    fired_ = true;
    lock.unlock();
    onHung_();
    return;
  }
}

}  // namespace lghd
