#include "lgh/bench/render_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "context/gl_context.hpp"
#include "frame_pipeline.hpp"
#include "lgh/error.hpp"
#include "lgh/testing/image_metrics.hpp"
#include "passes/lgh_lighting_common.hpp"
#include "scene/scene_cache.hpp"

namespace lgh::bench {
namespace {

// The frame's passes outside the hierarchy's construction, in frame order.
const char* const kRenderPasses[] = {
    "gbuffer",      "direct lighting",          "lgh interleave split",
    "lgh lighting", "lgh interleave composite", "composite"};
const char* const kLightingPasses[] = {"lgh interleave split", "lgh lighting",
                                       "lgh interleave composite"};
constexpr const char* kBuildPass = "lgh build";

struct RunConfig {
  int vpls = 0;
  LightingPath path = LightingPath::Compute;
  InterleaveMode interleave = InterleaveMode::None;
  int samples = 4;
  bool locked = false;
};

void checkOptions(const RenderBenchmarkOptions& o) {
  if (o.vplCounts.empty() || o.paths.empty() || o.interleaves.empty() || o.shadowSamples.empty()) {
    throw Error(ErrorCode::BadRequest,
                "give at least one VPL count, path, interleave and sample count");
  }
  for (int count : o.vplCounts) {
    if (count <= 0) {
      throw Error(ErrorCode::BadRequest, fmt::format("VPL count {} must be > 0", count), "vpls");
    }
  }
  for (int k : o.shadowSamples) {
    if (k < 1 || k > 8) {
      throw Error(ErrorCode::BadRequest, "shadow samples must be 1..8", "samples");
    }
  }
  for (LightingPath path : o.paths) {
    if (path == LightingPath::Auto) {
      throw Error(ErrorCode::BadRequest, "paths are raster or compute", "paths");
    }
  }
  if (o.width <= 0 || o.height <= 0 || o.timedIterations <= 0 || o.warmupIterations < 0) {
    throw Error(ErrorCode::BadRequest, "sizes and iterations must be > 0 (warm-up >= 0)");
  }
  if (o.locks != "paper" && o.locks != "none" && o.locks != "all") {
    throw Error(ErrorCode::BadRequest, "locks must be paper, none or all", "locks");
  }
  if (!(o.alpha > 0.0F)) throw Error(ErrorCode::BadRequest, "alpha must be > 0", "alpha");
}

bool lockedFor(const RenderBenchmarkOptions& o, InterleaveMode interleave) {
  if (o.locks == "all") return true;
  return o.locks == "paper" && interleave == InterleaveMode::Tiles4x4;
}

RenderRequest benchmarkRequest(const RenderBenchmarkOptions& o, const RunConfig& run) {
  RenderRequest request;
  request.output.width = o.width;
  request.output.height = o.height;
  LghSettings& lgh = request.settings.lgh;
  lgh.enabled = true;
  lgh.vplCount = run.vpls;
  lgh.seed = o.seed;
  lgh.vplIntensity = o.vplIntensity;
  lgh.alpha = o.alpha;
  lgh.path = run.path;
  lgh.interleave = run.interleave;
  lgh.shadowSamples = run.samples;
  lgh.lockedReservoir = run.locked;
  return request;
}

class BenchmarkSession {
 public:
  explicit BenchmarkSession(const RenderBenchmarkOptions& options)
      : options_(options),
        context_(GlContext::create(options.renderer)),
        cache_(options.renderer),
        scene_(cache_.get(SceneSource{}).entry) {}

  const DeviceInfo& device() const { return context_->info(); }

  // Renders `config` for `seconds` of wall time, untimed.
  void warmUp(const RunConfig& config, double seconds) {
    const RenderRequest request = benchmarkRequest(options_, config);
    const auto start = std::chrono::steady_clock::now();
    do {
      frame(request);
    } while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() <
             seconds);
  }

  FrameReport frame(const RenderRequest& request, LghFrameProbe* probe = nullptr) {
    FrameReport result;
    gl::GpuTimer timer;
    pipeline_.render(request, *scene_, timer, result, probe);
    return result;
  }

  // The brute-force image of `vpls` (rendered on the first call for that count, which appends
  // the frame's timing to `references`).
  const FloatImage& reference(int vpls, std::vector<RenderReference>& references) {
    auto it = references_.find(vpls);
    if (it != references_.end()) return it->second;
    RunConfig config{vpls, LightingPath::Compute, InterleaveMode::None, 1, false};
    LghFrameProbe probe;
    probe.bruteForce = true;
    const FrameReport result = frame(benchmarkRequest(options_, config), &probe);
    references.push_back({vpls, result.timings.get("lgh reference")});
    return references_.emplace(vpls, std::move(probe.reference)).first->second;
  }

  RenderRun run(const RunConfig& config, std::vector<RenderReference>& references) {
    const RenderRequest request = benchmarkRequest(options_, config);
    for (int i = 0; i < options_.warmupIterations; ++i) frame(request);
    TimingSamples samples;
    for (int i = 0; i < options_.timedIterations; ++i) {
      for (const TimingRow& row : frame(request).timings.rows) {
        if (row.clock == TimingRow::Clock::Gpu) samples.add(row.name, row.milliseconds);
      }
    }
    RenderRun out;
    out.vpls = config.vpls;
    out.path = config.path;
    out.interleave = config.interleave;
    out.shadowSamples = config.samples;
    out.locked = config.locked;
    for (const std::string& name : samples.names()) out.passes.push_back(samples.stats(name));
    auto sum = [&](auto&& names) {
      double total = 0.0;
      for (const char* name : names) total += samples.median(name);
      return total;
    };
    out.buildMs = samples.median(kBuildPass);
    out.lightingMs = sum(kLightingPasses);
    out.renderMs = sum(kRenderPasses);
    LghFrameProbe probe;
    probe.overdraw = options_.overdraw;
    frame(request, &probe);
    out.levels = probe.levels.levelCount;
    out.gridLights = probe.levels.totalLights;
    if (options_.overdraw) out.overdraw = overdrawStats(probe.overdrawCounts, probe.indirect);
    if (options_.reference) {
      const ImageError error =
          compareToReference(probe.indirect, reference(config.vpls, references));
      out.error = ReferenceError{error.relativeRmse, error.psnr};
    }
    return out;
  }

 private:
  RenderBenchmarkOptions options_;
  std::unique_ptr<GlContext> context_;
  SceneCache cache_;
  std::shared_ptr<CachedScene> scene_;
  FramePipeline pipeline_;
  std::map<int, FloatImage> references_;
};

}  // namespace

// Power-of-two histogram bins: Fig. 5 is a log heat map.
OverdrawStats overdrawStats(const std::vector<std::uint32_t>& counts, const FloatImage& coverage) {
  std::vector<std::uint32_t> covered;
  for (int y = 0; y < coverage.height; ++y) {
    for (int x = 0; x < coverage.width; ++x) {
      // Counts are in GL order (row 0 at the bottom), images top row first.
      if (coverage.pixel(x, coverage.height - 1 - y)[3] <= 0.0F) continue;
      covered.push_back(counts[static_cast<std::size_t>(y) * coverage.width + x]);
    }
  }
  OverdrawStats stats;
  if (covered.empty()) return stats;
  std::sort(covered.begin(), covered.end());
  double sum = 0.0;
  for (std::uint32_t c : covered) sum += c;
  auto quantile = [&](double q) {
    return covered[std::min(covered.size() - 1, static_cast<std::size_t>(q * covered.size()))];
  };
  std::uint64_t from = 0;
  for (std::uint64_t to = 1; from <= covered.back(); to *= 2) {
    const auto first = std::lower_bound(covered.begin(), covered.end(), from);
    const auto last = std::lower_bound(covered.begin(), covered.end(), to);
    stats.histogram.push_back({from, to, static_cast<std::size_t>(last - first)});
    from = to;
  }
  stats.pixels = covered.size();
  stats.mean = sum / static_cast<double>(covered.size());
  stats.max = covered.back();
  stats.p50 = quantile(0.5);
  stats.p95 = quantile(0.95);
  return stats;
}

RenderBenchmarkResult runRenderBenchmark(const RenderBenchmarkOptions& options) {
  checkOptions(options);
  BenchmarkSession session(options);
  session.warmUp({options.vplCounts.front(), options.paths.front(), options.interleaves.front(),
                  options.shadowSamples.front(), false},
                 options.warmupSeconds);
  RenderBenchmarkResult result;
  result.options = options;
  result.options.progress = nullptr;
  for (int vpls : options.vplCounts) {
    for (LightingPath path : options.paths) {
      for (InterleaveMode interleave : options.interleaves) {
        for (int samples : options.shadowSamples) {
          const RunConfig config{vpls, path, interleave, samples,
                                 path == LightingPath::Raster && lockedFor(options, interleave)};
          RenderRun run = session.run(config, result.references);
          if (options.progress) options.progress(run);
          result.runs.push_back(std::move(run));
        }
      }
    }
  }
  result.device = session.device();
  return result;
}

}  // namespace lgh::bench
