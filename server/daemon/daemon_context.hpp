// What every route handler works with: the configuration, the render queue, the job store and
// the metrics.
#pragma once

#include "benchmark_runner.hpp"
#include "config.hpp"
#include "jobs.hpp"
#include "metrics.hpp"
#include "render_queue.hpp"

namespace lghd {

struct DaemonContext {
  const DaemonConfig& config;
  lgh::RequestLimits requestLimits;
  RenderQueue& queue;
  Metrics& metrics;
  JobStore& jobs;
  BenchmarkRunner* benchmarks = nullptr;  // POST /v1/benchmark; none: 503
};

}  // namespace lghd
