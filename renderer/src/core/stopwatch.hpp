// Wall-clock time of CPU steps, for the timing table's CPU rows and the logs.
#pragma once

#include <chrono>

namespace lgh {

class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;

  Stopwatch() : start_(Clock::now()) {}
  double elapsedMs() const { return millisecondsBetween(start_, Clock::now()); }
  void restart() { start_ = Clock::now(); }
  Clock::time_point start() const { return start_; }

  static double millisecondsBetween(Clock::time_point from, Clock::time_point to) {
    return std::chrono::duration<double, std::milli>(to - from).count();
  }

 private:
  Clock::time_point start_;
};

}  // namespace lgh
