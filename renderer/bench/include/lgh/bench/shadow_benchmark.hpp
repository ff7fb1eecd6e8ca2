// The shadow benchmark behind `lgh-bench shadows`: full shadowed frames of the built-in demo scene
// with LGH indirect light (the paper's Table 3 frame: G-buffer, build, lighting, shadow rays,
// filter), for each tracing path the device has and each LGH shadow-sample count, timed by the
// frame's own timer rows (GL timestamps and Vulkan timestamps); and the acceleration structures'
// build time for the demo and for a generated scene of many triangles. The result is typed;
// lgh-bench prints it (server/bench/shadows.cpp, server/bench/result_json.cpp).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "lgh/bench/statistics.hpp"
#include "lgh/device_info.hpp"
#include "lgh/renderer_options.hpp"
#include "lgh/request.hpp"
#include "lgh/shadow_info.hpp"

namespace lgh::bench {

struct ShadowRun;

struct ShadowBenchmarkOptions {
  int width = 1280;
  int height = 720;
  int vpls = 100000;
  std::vector<int> shadowSamples{1, 4};  // the LGH's k
  std::vector<ShadowTracing> paths;      // empty: every path the device has
  int filterIterations = 4;
  int timedIterations = 10;
  int warmupIterations = 3;
  double warmupSeconds = 1.0;    // and at least this long: GPU clocks ramp up
  int buildTriangles = 1000000;  // the generated scene of the build benchmark; 0: none
  int buildIterations = 3;
  RendererOptions renderer;
  std::function<void(const ShadowRun&)> progress;
};

struct ShadowRun {
  ShadowTracing path = ShadowTracing::RayQuery;
  int shadowSamples = 4;
  int raysPerPixel = 0;  // the demo's 3 direct lights + k
  std::string transport;
  std::vector<TimingStats> passes;  // every row of the frame, GPU and CPU, in frame order
  double raysMs = 0.0;              // median of "shadow rays" (Vulkan)
  double filterMs = 0.0;            // median of "shadow filter" (GL)
  double frameGpuMs = 0.0;          // median sum of the frame's GPU rows
  double raysPerSecond = 0.0;       // pixels x rays per pixel / raysMs
};

struct ShadowBuild {
  std::string scene;
  std::size_t triangles = 0;
  TimingStats build;  // "shadow as build" (Vulkan timestamps)
};

struct ShadowBenchmarkResult {
  DeviceInfo device;
  ShadowInfo shadows;
  ShadowBenchmarkOptions options;
  std::vector<ShadowRun> runs;
  std::vector<ShadowBuild> builds;
};

// Throws lgh::Error: BadRequest for bad options, Unavailable when the machine cannot trace.
ShadowBenchmarkResult runShadowBenchmark(const ShadowBenchmarkOptions& options);

}  // namespace lgh::bench
