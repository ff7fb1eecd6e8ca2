// Prometheus metrics, kept in memory under one mutex and written in the text exposition format
// (version 0.0.4) on GET /metrics. Label values come from fixed sets (routes, outcomes) or from
// the renderer's pass names, so the series count stays bounded.
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "lgh/resource_stats.hpp"
#include "lgh/timing.hpp"

namespace lghd {

class Histogram {
 public:
  explicit Histogram(std::vector<double> upperBounds);
  void observe(double value);
  // Appends the _bucket, _sum and _count lines of `name` with `labels` ("" or `a="b",c="d"`).
  void write(std::string& out, const std::string& name, const std::string& labels) const;

 private:
  std::vector<double> bounds_;
  std::vector<std::uint64_t> counts_;  // per bucket, not cumulative
  double sum_ = 0.0;
  std::uint64_t count_ = 0;
};

// One render worker's values (its GPU: its place in --gpus), read at scrape time.
struct GpuGauges {
  int index = 0;
  bool ready = false;
  std::size_t queuedRenders = 0;
  bool rendering = false;
  std::uint64_t sceneCacheHits = 0;
  std::uint64_t sceneCacheMisses = 0;
  std::size_t sceneCacheEntries = 0;
  std::size_t sceneCacheBytes = 0;
  std::size_t framesInFlight = 0;
};

// Values read at scrape time from the queue and the renderers (totals over the workers).
struct RuntimeGauges {
  std::size_t queueDepth = 0;
  std::size_t queueCapacity = 0;
  bool rendering = false;
  bool ready = false;
  std::uint64_t sceneCacheHits = 0;
  std::uint64_t sceneCacheMisses = 0;
  std::size_t sceneCacheEntries = 0;
  std::size_t sceneCacheBytes = 0;
  std::size_t sceneCacheBudgetBytes = 0;
  // GL storage of freed scenes kept for later ones, outside the cache's budget.
  std::size_t sceneStorageKeptBytes = 0;
  // The shadow side: 1 ready, 0 unavailable, -1 no frame has asked for shadows yet.
  int shadowTracer = -1;
  lgh::ResourceStats resources;  // live GL objects and GPU memory, as of the last render
  // The output pipeline: frames between submission and the end of their encoding, their limit,
  // the encoder threads, and the read-back memory frames hold.
  std::size_t framesInFlight = 0;
  std::size_t frameLimit = 0;
  std::size_t encodeThreads = 0;
  std::size_t readbackBytes = 0;
  std::vector<GpuGauges> gpus;  // each render worker's (lghd_gpu_* families)
};

class Metrics {
 public:
  // One answered HTTP request: `route` is the route pattern (or "other"), not the raw path.
  void recordRequest(const std::string& route, const std::string& method, int status,
                     double seconds);
  // One render finished on the render thread: "ok", "error", "timeout" (the client was gone by
  // then: result discarded) or "skipped" (never started: deadline passed or cancelled).
  // `gpu` (>= 0): the render worker, counted in lghd_gpu_renders_total too.
  void recordRender(const std::string& outcome, int gpu = -1);
  void recordRenderTimes(const lgh::TimingTable& timings, double queueSeconds, bool cacheHit,
                         int gpu = -1);
  // How a render's shadows were made (its decision "shadows": ray-query, pipeline, none, off).
  void recordShadows(const std::string& shadows);
  // A render drawn before an earlier one of its batch whose scene was still being parsed.
  void recordDrawnAhead();
  void recordThumbnail(const std::string& status);
  // One frame encoded on an encoder thread: its wait for one (from read-back to the start of its
  // encoding) and the encoding itself, by output format (png, exr-half, exr-float).
  void recordEncode(std::string_view format, double waitSeconds, double encodeSeconds);

  std::string exposition(const RuntimeGauges& gauges) const;

 private:
  using Labels = std::string;
  mutable std::mutex mutex_;
  std::map<Labels, std::uint64_t> requests_;      // route, method, status
  std::map<Labels, Histogram> requestSeconds_;    // route
  std::map<Labels, std::uint64_t> renders_;       // outcome
  std::map<Labels, std::uint64_t> gpuRenders_;    // gpu, outcome
  std::map<Labels, Histogram> gpuRenderSeconds_;  // gpu
  std::map<Labels, Histogram> passSeconds_;       // pass, clock
  std::map<Labels, Histogram> renderSeconds_;     // cache
  Histogram queueWaitSeconds_{{0.001, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5, 10, 30}};
  std::map<Labels, std::uint64_t> thumbnails_;  // status
  std::map<Labels, std::uint64_t> shadows_;     // shadows
  std::uint64_t drawnAhead_ = 0;
  std::map<Labels, Histogram> encodeSeconds_;  // format
  Histogram encodeWaitSeconds_{
      {0.0001, 0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5}};
};

// `value` escaped for a label value: backslash, double quote and newline.
std::string escapeLabel(const std::string& value);

}  // namespace lghd
