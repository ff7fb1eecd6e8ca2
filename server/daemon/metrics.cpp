#include "metrics.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "version.hpp"

namespace lghd {
namespace {

const std::vector<double> kLatencyBuckets = {0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25,
                                             0.5,   1,      2.5,   5,    10,    30,   60};
const std::vector<double> kPassBuckets = {
    0.0001, 0.00025, 0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5};

std::string number(double value) { return fmt::format("{}", value); }

void header(std::string& out, const char* name, const char* type, const char* help) {
  out += fmt::format("# HELP {} {}\n# TYPE {} {}\n", name, help, name, type);
}

void counterLines(std::string& out, const char* name,
                  const std::map<std::string, std::uint64_t>& values) {
  for (const auto& [labels, value] : values) {
    out += fmt::format("{}{{{}}} {}\n", name, labels, value);
  }
}

void histogramLines(std::string& out, const char* name,
                    const std::map<std::string, Histogram>& values) {
  for (const auto& [labels, histogram] : values) histogram.write(out, name, labels);
}

void gauge(std::string& out, const char* name, const char* help, double value) {
  header(out, name, "gauge", help);
  out += fmt::format("{} {}\n", name, number(value));
}

template <class Map, class... Args>
auto& entry(Map& map, const std::string& labels, Args&&... args) {
  auto it = map.find(labels);
  if (it == map.end()) it = map.emplace(labels, typename Map::mapped_type(args...)).first;
  return it->second;
}

// One family of per-worker values, a line per worker.
template <class Value>
void gpuFamily(std::string& out, const char* name, const char* type, const char* help,
               const std::vector<GpuGauges>& gpus, Value value) {
  header(out, name, type, help);
  for (const GpuGauges& gpu : gpus) {
    out += fmt::format("{}{{gpu=\"{}\"}} {}\n", name, gpu.index, number(value(gpu)));
  }
}

void gpuGaugeLines(std::string& out, const std::vector<GpuGauges>& gpus) {
  const auto as = [](auto value) { return static_cast<double>(value); };
  gpuFamily(out, "lghd_gpu_ready", "gauge",
            "1 while the render worker of this GPU (its place in --gpus) is up and scheduled.",
            gpus, [](const GpuGauges& gpu) { return gpu.ready ? 1.0 : 0.0; });
  gpuFamily(out, "lghd_gpu_queue_depth", "gauge", "Renders waiting for this GPU's render thread.",
            gpus, [&](const GpuGauges& gpu) { return as(gpu.queuedRenders); });
  gpuFamily(out, "lghd_gpu_render_in_progress", "gauge",
            "1 while this GPU's render thread is rendering.", gpus,
            [](const GpuGauges& gpu) { return gpu.rendering ? 1.0 : 0.0; });
  gpuFamily(out, "lghd_gpu_frames_in_flight", "gauge",
            "This GPU's frames between submission and the end of their encoding.", gpus,
            [&](const GpuGauges& gpu) { return as(gpu.framesInFlight); });
  gpuFamily(out, "lghd_gpu_scene_cache_hits_total", "counter",
            "Scene cache lookups that hit, in this GPU's cache.", gpus,
            [&](const GpuGauges& gpu) { return as(gpu.sceneCacheHits); });
  gpuFamily(out, "lghd_gpu_scene_cache_misses_total", "counter",
            "Scene cache lookups that loaded and uploaded the scene to this GPU.", gpus,
            [&](const GpuGauges& gpu) { return as(gpu.sceneCacheMisses); });
  gpuFamily(out, "lghd_gpu_scene_cache_entries", "gauge", "Scenes held by this GPU's cache.", gpus,
            [&](const GpuGauges& gpu) { return as(gpu.sceneCacheEntries); });
  gpuFamily(out, "lghd_gpu_scene_cache_bytes", "gauge", "GPU memory held by this GPU's cache.",
            gpus, [&](const GpuGauges& gpu) { return as(gpu.sceneCacheBytes); });
}

}  // namespace

std::string escapeLabel(const std::string& value) {
  std::string escaped;
  for (char c : value) {
    if (c == '\\' || c == '"') escaped += '\\';
    if (c == '\n') {
      escaped += "\\n";
      continue;
    }
    escaped += c;
  }
  return escaped;
}

Histogram::Histogram(std::vector<double> upperBounds)
    : bounds_(std::move(upperBounds)), counts_(bounds_.size() + 1, 0) {}

void Histogram::observe(double value) {
  const auto bucket = std::lower_bound(bounds_.begin(), bounds_.end(), value) - bounds_.begin();
  ++counts_[static_cast<std::size_t>(bucket)];
  sum_ += value;
  ++count_;
}

void Histogram::write(std::string& out, const std::string& name, const std::string& labels) const {
  const std::string prefix = labels.empty() ? "" : labels + ",";
  std::uint64_t cumulative = 0;
  for (std::size_t i = 0; i < bounds_.size(); ++i) {
    cumulative += counts_[i];
    out +=
        fmt::format("{}_bucket{{{}le=\"{}\"}} {}\n", name, prefix, number(bounds_[i]), cumulative);
  }
  out += fmt::format("{}_bucket{{{}le=\"+Inf\"}} {}\n", name, prefix, count_);
  const std::string braces = labels.empty() ? "" : "{" + labels + "}";
  out +=
      fmt::format("{}_sum{} {}\n{}_count{} {}\n", name, braces, number(sum_), name, braces, count_);
}

void Metrics::recordRequest(const std::string& route, const std::string& method, int status,
                            double seconds) {
  const std::string routeLabel = fmt::format("route=\"{}\"", escapeLabel(route));
  std::lock_guard lock(mutex_);
  ++requests_[fmt::format("{},method=\"{}\",status=\"{}\"", routeLabel, escapeLabel(method),
                          status)];
  entry(requestSeconds_, routeLabel, kLatencyBuckets).observe(seconds);
}

void Metrics::recordRender(const std::string& outcome, int gpu) {
  std::lock_guard lock(mutex_);
  ++renders_[fmt::format("outcome=\"{}\"", outcome)];
  if (gpu >= 0) ++gpuRenders_[fmt::format("gpu=\"{}\",outcome=\"{}\"", gpu, outcome)];
}

void Metrics::recordRenderTimes(const lgh::TimingTable& timings, double queueSeconds, bool cacheHit,
                                int gpu) {
  std::lock_guard lock(mutex_);
  queueWaitSeconds_.observe(queueSeconds);
  for (const lgh::TimingRow& row : timings.rows) {
    if (row.name == "queue") continue;  // lghd_queue_wait_seconds
    if (row.name == "total") {
      entry(renderSeconds_, cacheHit ? "scene_cache=\"hit\"" : "scene_cache=\"miss\"",
            kLatencyBuckets)
          .observe(row.milliseconds / 1000.0);
      if (gpu >= 0) {
        entry(gpuRenderSeconds_, fmt::format("gpu=\"{}\"", gpu), kLatencyBuckets)
            .observe(row.milliseconds / 1000.0);
      }
      continue;
    }
    const char* clock = row.clock == lgh::TimingRow::Clock::Gpu ? "gpu" : "cpu";
    entry(passSeconds_, fmt::format("pass=\"{}\",clock=\"{}\"", escapeLabel(row.name), clock),
          kPassBuckets)
        .observe(row.milliseconds / 1000.0);
  }
}

void Metrics::recordShadows(const std::string& shadows) {
  std::lock_guard lock(mutex_);
  ++shadows_[fmt::format("shadows=\"{}\"", escapeLabel(shadows))];
}

void Metrics::recordDrawnAhead() {
  std::lock_guard lock(mutex_);
  ++drawnAhead_;
}

void Metrics::recordEncode(std::string_view format, double waitSeconds, double encodeSeconds) {
  std::lock_guard lock(mutex_);
  encodeWaitSeconds_.observe(waitSeconds);
  entry(encodeSeconds_, fmt::format("format=\"{}\"", escapeLabel(std::string(format))),
        kPassBuckets)
      .observe(encodeSeconds);
}

void Metrics::recordThumbnail(const std::string& status) {
  std::lock_guard lock(mutex_);
  ++thumbnails_[fmt::format("status=\"{}\"", status)];
}

std::string Metrics::exposition(const RuntimeGauges& gauges) const {
  std::string out;
  header(out, "lghd_build_info", "gauge", "Build of this daemon; the value is always 1.");
  out += fmt::format("lghd_build_info{{version=\"{}\",image_io=\"{}\"}} 1\n", kVersion, kImageIo);
  gauge(out, "lghd_ready", "1 once the GL context is up and the self-test render passed.",
        gauges.ready ? 1 : 0);
  gauge(out, "lghd_queue_depth", "Renders waiting for the render thread.",
        static_cast<double>(gauges.queueDepth));
  gauge(out, "lghd_queue_capacity", "Renders that may wait before requests get 429.",
        static_cast<double>(gauges.queueCapacity));
  gauge(out, "lghd_render_in_progress", "1 while the render thread is rendering.",
        gauges.rendering ? 1 : 0);
  header(out, "lghd_scene_cache_hits_total", "counter", "Scene cache lookups that hit.");
  out += fmt::format("lghd_scene_cache_hits_total {}\n", gauges.sceneCacheHits);
  header(out, "lghd_scene_cache_misses_total", "counter",
         "Scene cache lookups that loaded and uploaded the scene.");
  out += fmt::format("lghd_scene_cache_misses_total {}\n", gauges.sceneCacheMisses);
  gauge(out, "lghd_scene_cache_entries", "Scenes held by the scene cache.",
        static_cast<double>(gauges.sceneCacheEntries));
  gauge(out, "lghd_scene_cache_bytes", "GPU memory held by cached scenes.",
        static_cast<double>(gauges.sceneCacheBytes));
  gauge(out, "lghd_scene_cache_budget_bytes", "GPU memory budget of the scene cache.",
        static_cast<double>(gauges.sceneCacheBudgetBytes));
  gauge(out, "lghd_scene_storage_kept_bytes",
        "GPU memory of freed scenes' textures and buffers kept for later scenes (outside the "
        "scene cache's budget).",
        static_cast<double>(gauges.sceneStorageKeptBytes));
  gauge(out, "lghd_shadow_tracer_ready",
        "1 when the Vulkan shadow tracer is up, 0 when this machine cannot trace shadows (see "
        "/v1/info), -1 until a frame has asked for shadows.",
        gauges.shadowTracer);
  header(out, "lghd_gl_objects", "gauge",
         "Live GL objects by kind (a leak shows as growth over many renders).");
  for (const auto& [kind, count] : gauges.resources.glObjects) {
    out += fmt::format("lghd_gl_objects{{kind=\"{}\"}} {}\n", escapeLabel(kind), count);
  }
  const auto bytesOrUnknown = [](std::int64_t kib) {
    return kib >= 0 ? static_cast<double>(kib) * 1024.0 : -1.0;
  };
  gauge(out, "lghd_gpu_memory_available_bytes",
        "GPU memory available as the driver reports it (GL_NVX_gpu_memory_info); -1 where it "
        "does not say.",
        bytesOrUnknown(gauges.resources.gpuMemoryAvailableKiB));
  gauge(out, "lghd_gpu_memory_total_bytes",
        "GPU memory in all (GL_NVX_gpu_memory_info); -1 where the driver does not say.",
        bytesOrUnknown(gauges.resources.gpuMemoryTotalKiB));
  gauge(out, "lghd_frames_in_flight",
        "Frames between submission to the GPU and the end of their encoding.",
        static_cast<double>(gauges.framesInFlight));
  gauge(out, "lghd_frames_in_flight_limit", "--frames-in-flight: the render thread waits beyond.",
        static_cast<double>(gauges.frameLimit));
  gauge(out, "lghd_encode_threads", "Threads encoding finished frames (--encode-threads).",
        static_cast<double>(gauges.encodeThreads));
  gauge(out, "lghd_readback_bytes",
        "Read-back memory held by frames in flight (their pixels, until encoded).",
        static_cast<double>(gauges.readbackBytes));

  gpuGaugeLines(out, gauges.gpus);

  std::lock_guard lock(mutex_);
  header(out, "lghd_http_requests_total", "counter",
         "HTTP requests answered, by route and status.");
  counterLines(out, "lghd_http_requests_total", requests_);
  header(out, "lghd_http_request_duration_seconds", "histogram",
         "Time from the request's headers to its answer, by route.");
  histogramLines(out, "lghd_http_request_duration_seconds", requestSeconds_);
  header(out, "lghd_renders_total", "counter",
         "Renders by outcome: ok, error, timeout (finished after its deadline, discarded), "
         "skipped (deadline passed or cancelled before it started).");
  counterLines(out, "lghd_renders_total", renders_);
  header(
      out, "lghd_render_duration_seconds", "histogram",
      "Render time from the render thread taking the request to its encoded image (the \"total\" "
      "row), by scene-cache result.");
  histogramLines(out, "lghd_render_duration_seconds", renderSeconds_);
  header(out, "lghd_render_pass_seconds", "histogram",
         "Time of each pass of a render: clock=gpu from timer queries, clock=cpu from a steady "
         "clock.");
  histogramLines(out, "lghd_render_pass_seconds", passSeconds_);
  header(out, "lghd_queue_wait_seconds", "histogram", "Time renders waited in the queue.");
  queueWaitSeconds_.write(out, "lghd_queue_wait_seconds", "");
  header(out, "lghd_encode_seconds", "histogram",
         "Time an encoder thread took to encode a frame, by output format.");
  histogramLines(out, "lghd_encode_seconds", encodeSeconds_);
  header(out, "lghd_encode_wait_seconds", "histogram",
         "Time finished frames waited for an encoder thread.");
  encodeWaitSeconds_.write(out, "lghd_encode_wait_seconds", "");
  header(out, "lghd_thumbnails_total", "counter", "Thumbnails rendered in batches, by status.");
  counterLines(out, "lghd_thumbnails_total", thumbnails_);
  header(out, "lghd_render_shadows_total", "counter",
         "Renders by how their shadows were traced: ray-query, pipeline, none (the machine cannot "
         "trace: unshadowed with a warning), off (the request asked for none).");
  counterLines(out, "lghd_render_shadows_total", shadows_);
  header(out, "lghd_renders_drawn_ahead_total", "counter",
         "Renders of a batch drawn before an earlier one whose scene was still being parsed.");
  out += fmt::format("lghd_renders_drawn_ahead_total {}\n", drawnAhead_);
  header(out, "lghd_gpu_renders_total", "counter",
         "Renders by render worker (gpu: its place in --gpus) and outcome, as lghd_renders_total.");
  counterLines(out, "lghd_gpu_renders_total", gpuRenders_);
  header(out, "lghd_gpu_render_duration_seconds", "histogram",
         "Render time (the \"total\" row) by render worker.");
  histogramLines(out, "lghd_gpu_render_duration_seconds", gpuRenderSeconds_);
  return out;
}

}  // namespace lghd
