// A GPU reset while serving (simulated: LGH_DEBUG_CONTEXT_LOSS_AFTER makes the renderer report a
// lost context after N frames): the render that meets it fails with 503, the daemon makes its
// renderer again (not ready meanwhile), and the next render is the golden image again.
// A render thread stuck in a driver call (simulated by --test-render-delay-ms): the watchdog
// answers, and lghd exits 3 for its supervisor to start a fresh process.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <thread>

#include "daemon_process.hpp"
#include "lgh/image.hpp"

namespace {

using lghd::test::DaemonProcess;

const char* const kGoldenRequest = R"({"output": {"width": 160, "height": 120}})";

// Mean absolute error (0..255) of an 8-bit PNG against tests/golden/demo_160x120.png.
double errorAgainstGolden(const std::string& png) {
  const auto golden = lgh::image_io::decode(
      lgh::image_io::readFile(std::string(LGH_TEST_DATA_DIR) + "/golden/demo_160x120.png"),
      "golden");
  const auto actual =
      lgh::image_io::decode(std::vector<std::uint8_t>(png.begin(), png.end()), "answer");
  if (actual.width != golden.width || actual.height != golden.height ||
      actual.pixels8.size() != golden.pixels8.size()) {
    return 255.0;
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < golden.pixels8.size(); ++i) {
    sum += std::abs(int{actual.pixels8[i]} - int{golden.pixels8[i]});
  }
  return sum / static_cast<double>(golden.pixels8.size());
}

TEST(HttpRecovery, ALostContextFailsOneRenderAndTheDaemonRecovers) {
  // The self-test render is frame 1: frames 2 and 3 render, frame 4 meets the "reset".
  DaemonProcess daemon({}, {"LGH_DEBUG_CONTEXT_LOSS_AFTER=3"});
  auto http = daemon.client();
  for (int frame = 2; frame <= 3; ++frame) {
    const auto ok = http->Post("/v1/render", kGoldenRequest, "application/json");
    ASSERT_EQ(ok->status, 200) << ok->body;
  }
  const auto lost = http->Post("/v1/render", kGoldenRequest, "application/json");
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->status, 503) << lost->body;
  EXPECT_NE(lost->body.find("GL context was lost"), std::string::npos) << lost->body;
  // Ready again once the new renderer has passed its self-test.
  bool ready = false;
  for (int i = 0; i < 600 && !ready; ++i) {
    ready = http->Get("/readyz")->status == 200;
    if (!ready) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(ready) << daemon.log();
  const auto again = http->Post("/v1/render", kGoldenRequest, "application/json");
  ASSERT_EQ(again->status, 200) << again->body;
  EXPECT_LE(errorAgainstGolden(again->body), 0.5)
      << "the recovered renderer draws the golden image";
  EXPECT_NE(daemon.log().find("renderer_reset"), std::string::npos);
}

TEST(HttpRecovery, AHungRenderMakesTheDaemonExitForItsSupervisor) {
  DaemonProcess daemon(
      {"--test-render-delay-ms", "4000", "--watchdog-seconds", "0.5", "--grace-seconds", "30"});
  auto http = daemon.client();
  httplib::Headers headers{{"X-Lgh-Deadline-Ms", "300"}};
  const auto start = std::chrono::steady_clock::now();
  const auto stuck = http->Post("/v1/render", headers, kGoldenRequest, "application/json");
  ASSERT_TRUE(stuck);
  EXPECT_EQ(stuck->status, 504) << stuck->body;
  // The watchdog fires 0.5 s past the deadline; lghd does not wait out the grace for a render
  // that cannot end, nor the render thread.
  bool exited = false;
  while (!exited && std::chrono::steady_clock::now() - start < std::chrono::seconds(3)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    exited = daemon.exited();
  }
  ASSERT_TRUE(exited) << daemon.log();
  EXPECT_EQ(daemon.stop(SIGTERM, std::chrono::milliseconds(0)), 3);
  EXPECT_NE(daemon.log().find("render_hung"), std::string::npos) << daemon.log();
}

}  // namespace
