// The hand-off benchmark behind `lgh-bench handoff`: what it costs to hand a batch of shadow rays
// from the GL frame to the Vulkan tracer and back, in this process (the design lghd uses), and
// what a tracer in a separate process would add on top: a request and a reply over a Unix socket
// to a child process each frame, and the file descriptors of the shared buffers sent over the
// socket (SCM_RIGHTS) whenever they are reallocated. docs/SHADOWS.md weighs the two designs with
// these figures.
#pragma once

#include <string>

#include "lgh/bench/statistics.hpp"
#include "lgh/device_info.hpp"
#include "lgh/renderer_options.hpp"
#include "lgh/shadow_info.hpp"

namespace lgh::bench {

struct HandoffBenchmarkOptions {
  int iterations = 1000;
  int warmupIterations = 50;
  RendererOptions renderer;
};

struct HandoffBenchmarkResult {
  DeviceInfo device;
  ShadowInfo shadows;
  std::string transport;  // interop, interop-finish or staging
  HandoffBenchmarkOptions options;
  // One ray from one pixel, in an empty scene: GL writes the batch, hands it to Vulkan, Vulkan
  // traces it, GL reads the visibility back (glFinish included): the fixed cost of a batch.
  TimingStats inProcessBatch;
  // A 64-byte request and its reply between this process and a child over a socketpair.
  TimingStats socketRoundTrip;
  // Three file descriptors sent to the child with SCM_RIGHTS and acknowledged.
  TimingStats fdPassing;
};

// Throws lgh::Error(Unavailable) when the machine cannot trace.
HandoffBenchmarkResult runHandoffBenchmark(const HandoffBenchmarkOptions& options);

}  // namespace lgh::bench
