// What every route handler works with: the configuration, the render queue and the metrics.
#pragma once

#include "config.hpp"
#include "metrics.hpp"
#include "render_queue.hpp"

namespace lghd {

struct DaemonContext {
  const DaemonConfig& config;
  lgh::RequestLimits requestLimits;
  RenderQueue& queue;
  Metrics& metrics;
};

}  // namespace lghd
