// clock.hpp: the durations the daemon reports (queue and render milliseconds, request seconds).
#include <gtest/gtest.h>

#include <chrono>

#include "clock.hpp"

namespace lghd {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;

TEST(DaemonClock, DurationsBetweenTwoPoints) {
  const Clock::time_point start = Clock::now();
  EXPECT_DOUBLE_EQ(millisecondsBetween(start, start + microseconds(1500)), 1.5);
  EXPECT_DOUBLE_EQ(secondsBetween(start, start + milliseconds(250)), 0.25);
  EXPECT_DOUBLE_EQ(millisecondsBetween(start, start), 0.0);
  EXPECT_DOUBLE_EQ(millisecondsBetween(start + milliseconds(2), start), -2.0);
}

TEST(DaemonClock, SinceCountsUpToNow) {
  const Clock::time_point past = Clock::now() - milliseconds(40);
  const double ms = millisecondsSince(past);
  const double seconds = secondsSince(past);
  EXPECT_GE(ms, 40.0);
  EXPECT_GE(seconds, 0.040);
  EXPECT_GE(seconds * 1000.0, ms) << "measured later, from the same point";
  EXPECT_LT(ms, 40.0 + 60'000.0);
  EXPECT_LE(millisecondsSince(Clock::now() + milliseconds(1000)), 0.0) << "a point ahead";
}

}  // namespace
}  // namespace lghd
