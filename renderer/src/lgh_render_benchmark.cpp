#include "lgh/lgh_render_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "context/gl_context.hpp"
#include "frame_pipeline.hpp"
#include "lgh/error.hpp"
#include "lgh/image_metrics.hpp"
#include "passes/lgh_lighting_common.hpp"
#include "scene/scene_cache.hpp"

namespace lgh {
namespace {

// The frame's passes outside the hierarchy's construction, in frame order.
const char* const kRenderPasses[] = {
    "gbuffer",      "direct lighting",          "lgh interleave split",
    "lgh lighting", "lgh interleave composite", "composite"};
const char* const kLightingPasses[] = {"lgh interleave split", "lgh lighting",
                                       "lgh interleave composite"};
constexpr const char* kBuildPass = "lgh build";

struct Samples {
  std::vector<std::string> order;  // pass names in first-seen order
  std::map<std::string, std::vector<double>> values;
  void add(const TimingTable& table) {
    for (const TimingRow& row : table.rows) {
      if (row.clock != TimingRow::Clock::Gpu) continue;
      if (!values.contains(row.name)) order.push_back(row.name);
      values[row.name].push_back(row.milliseconds);
    }
  }
};

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

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

// Overdraw over the covered pixels, with power-of-two histogram bins (Fig. 5 is a log heat map).
nlohmann::json overdrawStats(const std::vector<std::uint32_t>& counts, const FloatImage& coverage) {
  std::vector<std::uint32_t> covered;
  for (int y = 0; y < coverage.height; ++y) {
    for (int x = 0; x < coverage.width; ++x) {
      // Counts are in GL order (row 0 at the bottom), images top row first.
      if (coverage.pixel(x, coverage.height - 1 - y)[3] <= 0.0F) continue;
      covered.push_back(counts[static_cast<std::size_t>(y) * coverage.width + x]);
    }
  }
  if (covered.empty()) return {{"pixels", 0}};
  std::sort(covered.begin(), covered.end());
  double sum = 0.0;
  for (std::uint32_t c : covered) sum += c;
  auto quantile = [&](double q) {
    return covered[std::min(covered.size() - 1, static_cast<std::size_t>(q * covered.size()))];
  };
  nlohmann::json histogram = nlohmann::json::array();
  std::uint64_t from = 0;
  for (std::uint64_t to = 1; from <= covered.back(); to *= 2) {
    const auto first = std::lower_bound(covered.begin(), covered.end(), from);
    const auto last = std::lower_bound(covered.begin(), covered.end(), to);
    histogram.push_back({{"from", from}, {"to", to}, {"pixels", last - first}});
    from = to;
  }
  return {{"pixels", covered.size()}, {"mean", sum / static_cast<double>(covered.size())},
          {"max", covered.back()},    {"p50", quantile(0.5)},
          {"p95", quantile(0.95)},    {"histogram", histogram}};
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

  // The brute-force image of `vpls` (rendered on the first call for that count).
  const FloatImage& reference(int vpls, nlohmann::json& references) {
    auto it = references_.find(vpls);
    if (it != references_.end()) return it->second;
    RunConfig config{vpls, LightingPath::Compute, InterleaveMode::None, 1, false};
    LghFrameProbe probe;
    probe.bruteForce = true;
    const FrameReport result = frame(benchmarkRequest(options_, config), &probe);
    references.push_back({{"vpls", vpls}, {"bruteforce_ms", result.timings.get("lgh reference")}});
    return references_.emplace(vpls, std::move(probe.reference)).first->second;
  }

  nlohmann::json run(const RunConfig& config, nlohmann::json& references) {
    const RenderRequest request = benchmarkRequest(options_, config);
    for (int i = 0; i < options_.warmupIterations; ++i) frame(request);
    Samples samples;
    for (int i = 0; i < options_.timedIterations; ++i) samples.add(frame(request).timings);
    nlohmann::json out = timings(samples);
    LghFrameProbe probe;
    probe.overdraw = options_.overdraw;
    frame(request, &probe);
    out["levels"] = probe.levels.levelCount;
    out["grid_lights"] = probe.levels.totalLights;
    if (options_.overdraw) out["overdraw"] = overdrawStats(probe.overdrawCounts, probe.indirect);
    if (options_.reference) {
      const ImageError error =
          compareToReference(probe.indirect, reference(config.vpls, references));
      out["relative_rmse"] = error.relativeRmse;
      out["psnr"] = std::isfinite(error.psnr) ? nlohmann::json(error.psnr) : nlohmann::json("inf");
    }
    return out;
  }

 private:
  static nlohmann::json timings(Samples& samples) {
    nlohmann::json passes = nlohmann::json::array();
    std::map<std::string, double> medians;
    for (const std::string& name : samples.order) {
      const auto& values = samples.values[name];
      medians[name] = median(values);
      passes.push_back({{"name", name},
                        {"median_ms", medians[name]},
                        {"min_ms", *std::min_element(values.begin(), values.end())},
                        {"max_ms", *std::max_element(values.begin(), values.end())}});
    }
    auto sum = [&](auto&& names) {
      double total = 0.0;
      for (const char* name : names) total += medians.contains(name) ? medians[name] : 0.0;
      return total;
    };
    return {{"passes", passes},
            {"build_ms", medians[kBuildPass]},
            {"lighting_ms", sum(kLightingPasses)},
            {"render_ms", sum(kRenderPasses)}};
  }

  RenderBenchmarkOptions options_;
  std::unique_ptr<GlContext> context_;
  SceneCache cache_;
  std::shared_ptr<CachedScene> scene_;
  FramePipeline pipeline_;
  std::map<int, FloatImage> references_;
};

std::string progressLine(const nlohmann::json& run) {
  std::string line = fmt::format(
      "lgh render: {} VPLs, {}, interleave {}, {} sample(s){}: lighting {:.3f} ms, render {:.3f} "
      "ms",
      run["vpls"].get<int>(), run["path"].get<std::string>(), run["interleave"].get<std::string>(),
      run["shadow_samples"].get<int>(), run["locked"].get<bool>() ? ", locked" : "",
      run["lighting_ms"].get<double>(), run["render_ms"].get<double>());
  if (run.contains("relative_rmse")) {
    line += fmt::format(", rel. RMSE {:.4f}", run["relative_rmse"].get<double>());
  }
  if (run.contains("overdraw") && run["overdraw"].contains("mean")) {
    line += fmt::format(", overdraw {:.1f}", run["overdraw"]["mean"].get<double>());
  }
  return line;
}

nlohmann::json settingsJson(const RenderBenchmarkOptions& o) {
  nlohmann::json paths = nlohmann::json::array();
  for (LightingPath path : o.paths) paths.push_back(std::string(enumName(path)));
  nlohmann::json interleaves = nlohmann::json::array();
  for (InterleaveMode mode : o.interleaves) interleaves.push_back(std::string(enumName(mode)));
  return {{"width", o.width},
          {"height", o.height},
          {"vpls", o.vplCounts},
          {"paths", paths},
          {"interleaves", interleaves},
          {"shadow_samples", o.shadowSamples},
          {"alpha", o.alpha},
          {"locks", o.locks},
          {"warmup_seconds", o.warmupSeconds},
          {"warmup_iterations", o.warmupIterations},
          {"timed_iterations", o.timedIterations},
          {"seed", o.seed},
          {"vpl_intensity", o.vplIntensity},
          {"scene", "demo"}};
}

}  // namespace

nlohmann::json runRenderBenchmark(const RenderBenchmarkOptions& options) {
  checkOptions(options);
  BenchmarkSession session(options);
  session.warmUp({options.vplCounts.front(), options.paths.front(), options.interleaves.front(),
                  options.shadowSamples.front(), false},
                 options.warmupSeconds);
  nlohmann::json runs = nlohmann::json::array();
  nlohmann::json references = nlohmann::json::array();
  for (int vpls : options.vplCounts) {
    for (LightingPath path : options.paths) {
      for (InterleaveMode interleave : options.interleaves) {
        for (int samples : options.shadowSamples) {
          const RunConfig config{vpls, path, interleave, samples,
                                 path == LightingPath::Raster && lockedFor(options, interleave)};
          nlohmann::json run = session.run(config, references);
          run["vpls"] = vpls;
          run["path"] = std::string(enumName(path));
          run["interleave"] = std::string(enumName(interleave));
          run["shadow_samples"] = samples;
          run["locked"] = config.locked;
          if (options.progress) options.progress(progressLine(run));
          runs.push_back(std::move(run));
        }
      }
    }
  }
  return {{"benchmark", "lgh-render"},
          {"device", session.device().toJson()},
          {"settings", settingsJson(options)},
          {"references", references},
          {"runs", runs}};
}

}  // namespace lgh
