// Shadows through the real daemon: a shadowed render comes back with its shadow decisions in
// X-Lgh-Paths and its Vulkan rows in the timing table; the daemon, with its Vulkan device in the
// process, starts, renders shadowed images and stops with exit status 0 under SIGTERM, again and
// again; /metrics counts renders by how their shadows were made.
#include <gtest/gtest.h>

#include <csignal>
#include <string>

#include <nlohmann/json.hpp>

#include "daemon_process.hpp"

namespace {

using json = nlohmann::json;
using lghd::test::DaemonProcess;

const std::string kShadowedRequest =
    R"({"settings": {"shadows": "on", "lgh": {"enabled": true, "vpl_count": 500}},
        "output": {"width": 48, "height": 32}})";

TEST(HttpShadows, ShadowedRendersAndCleanStopsManyTimesInARow) {
  for (int round = 0; round < 4; ++round) {
    DaemonProcess daemon;
    auto http = daemon.client();
    const auto png = http->Post("/v1/render", kShadowedRequest, "application/json");
    ASSERT_TRUE(png) << "round " << round;
    ASSERT_EQ(png->status, 200) << png->body;
    const json paths = json::parse(png->get_header_value("X-Lgh-Paths"));
    EXPECT_NE(paths.value("shadows", ""), "none") << paths.dump();
    EXPECT_EQ(paths.value("shadow_rays", ""), "7") << paths.dump();  // 3 lights + k = 4

    httplib::Headers accept{{"Accept", "application/json"}};
    const auto summary = http->Post("/v1/render", accept, kShadowedRequest, "application/json");
    ASSERT_EQ(summary->status, 200);
    const json timings = json::parse(summary->body).at("timings");
    bool traced = false;
    for (const json& row : timings) traced = traced || row.at("pass") == "shadow rays";
    EXPECT_TRUE(traced) << timings.dump();

    const auto metrics = http->Get("/metrics");
    ASSERT_EQ(metrics->status, 200);
    EXPECT_NE(metrics->body.find("lghd_shadow_tracer_ready 1"), std::string::npos);
    EXPECT_NE(metrics->body.find("lghd_render_shadows_total{shadows=\""), std::string::npos);
    EXPECT_EQ(daemon.stop(SIGTERM, std::chrono::seconds(30)), 0) << "round " << round << ":\n"
                                                                 << daemon.log();
  }
}

}  // namespace
