// The daemon's clock, and the durations measured on it that logs, metrics and headers report.
#pragma once

#include <chrono>

namespace lghd {

using Clock = std::chrono::steady_clock;

// From `from` to `to`, fractional (negative when `to` comes first).
inline double secondsBetween(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}
inline double millisecondsBetween(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

// From `from` to now.
inline double secondsSince(Clock::time_point from) { return secondsBetween(from, Clock::now()); }
inline double millisecondsSince(Clock::time_point from) {
  return millisecondsBetween(from, Clock::now());
}

}  // namespace lghd
