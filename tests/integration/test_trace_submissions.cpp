// The tracer's submission slots (vk/trace_submissions.hpp) on a real Vulkan device (lavapipe in
// CI): each submission's GPU time is banked under its number and handed out once, to whoever asks
// for the submissions up to a number: a frame reads its own when it is taken, which lets the
// render thread draw the next frame while this one's rays are traced.
#include <gtest/gtest.h>

#include "vk/trace_submissions.hpp"
#include "vk/vulkan_device.hpp"
#include "vulkan_device_test.hpp"

namespace {

using lgh::vk::TraceSubmissions;

class TraceSubmissionsTest : public lgh::test::VulkanDeviceTest {
 protected:
  // Records a submission that does nothing but its timestamps.
  static std::uint64_t submit(TraceSubmissions& submissions) {
    const std::uint32_t slot = submissions.acquire();
    const ::vk::raii::CommandBuffer& commands = submissions.commands(slot);
    commands.begin({});
    submissions.timestamps().begin(commands, slot);
    submissions.timestamps().end(commands, slot);
    commands.end();
    submissions.submit(slot, {}, {}, {});
    return submissions.lastSubmission();
  }
};

TEST_F(TraceSubmissionsTest, SubmissionsAreNumberedFromOne) {
  TraceSubmissions submissions(*device, 3);
  EXPECT_EQ(submissions.lastSubmission(), 0U);
  EXPECT_EQ(submit(submissions), 1U);
  EXPECT_EQ(submit(submissions), 2U);
  submissions.retireAll();
}

// A frame asks for its own submissions; the later ones stay banked for their frames. (That it
// does not wait for them is not shown here: lavapipe's query read waits for the whole queue, so a
// later submission held back by an event would hold the read too.)
TEST_F(TraceSubmissionsTest, TimesUpToANumberLeaveTheLaterOnesForTheirFrames) {
  TraceSubmissions submissions(*device, 4);
  const std::uint64_t first = submit(submissions);
  const std::uint64_t second = submit(submissions);
  const std::uint64_t third = submit(submissions);
  EXPECT_GE(submissions.takeGpuMs(first), 0.0);
  EXPECT_EQ(submissions.takeGpuMs(first), 0.0) << "handed out already";
  EXPECT_GE(submissions.takeGpuMs(third), 0.0);  // the second and the third
  EXPECT_EQ(submissions.takeGpuMs(second), 0.0) << "the third's call took the second's too";
  EXPECT_EQ(submissions.takeGpuMs(third), 0.0);
}

TEST_F(TraceSubmissionsTest, EachTimeIsHandedOutOnce) {
  TraceSubmissions submissions(*device, 2);
  // More submissions than slots: the first ones are retired (banked) by acquire().
  for (int i = 0; i < 5; ++i) submit(submissions);
  submissions.retireAll();
  (void)submissions.takeGpuMs(submissions.lastSubmission());
  EXPECT_EQ(submissions.takeGpuMs(submissions.lastSubmission()), 0.0) << "nothing left to hand out";
  const std::uint64_t next = submit(submissions);
  EXPECT_EQ(submissions.takeGpuMs(next - 1), 0.0) << "the earlier ones were handed out already";
  EXPECT_GE(submissions.takeGpuMs(next), 0.0);
}

}  // namespace
