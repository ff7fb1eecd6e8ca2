#include "lgh/bench/shadow_benchmark.hpp"

#include <cmath>
#include <cstring>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/stopwatch.hpp"
#include "lgh/error.hpp"
#include "lgh/renderer.hpp"

namespace lgh::bench {
namespace {

using json = nlohmann::json;

void checkOptions(const ShadowBenchmarkOptions& o) {
  if (o.width <= 0 || o.height <= 0 || o.vpls <= 0 || o.timedIterations <= 0 ||
      o.warmupIterations < 0 || o.buildTriangles < 0 || o.buildIterations <= 0) {
    throw Error(ErrorCode::BadRequest, "sizes, VPLs and iterations must be > 0 (warm-up >= 0)");
  }
  for (int k : o.shadowSamples) {
    if (k < 1 || k > 8) throw Error(ErrorCode::BadRequest, "shadow samples are 1..8", "samples");
  }
}

RenderRequest frameRequest(const ShadowBenchmarkOptions& o, ShadowTracing path, int k) {
  json request = {
      {"output", {{"width", o.width}, {"height", o.height}, {"format", "exr-float"}}},
      {"settings",
       {{"shadows", "on"},
        {"shadow_path", std::string(enumName(path))},
        {"shadow_filter_iterations", o.filterIterations},
        {"lgh",
         {{"enabled", true}, {"vpl_count", o.vpls}, {"shadow_samples", k}, {"path", "compute"}}}}}};
  RenderRequest parsed = parseRenderRequest(request, RequestLimits{});
  return parsed;
}

// Frames back to back, unencoded: a CPU pause between frames (an EXR encode takes 0.2 s) lets
// the GPU lower its clocks, and the next frame's first passes would be timed at those clocks.
ShadowRun runFrames(Renderer& renderer, const ShadowBenchmarkOptions& o, ShadowTracing path,
                    int k) {
  const RenderRequest request = frameRequest(o, path, k);
  const Stopwatch warmup;
  for (int i = 0; i < o.warmupIterations || warmup.elapsedMs() < 1000.0 * o.warmupSeconds; ++i) {
    renderer.renderFrame(request);
  }
  TimingSamples samples;
  std::vector<double> gpuTotals;
  ShadowRun run;
  run.path = path;
  run.shadowSamples = k;
  for (int i = 0; i < o.timedIterations; ++i) {
    const RenderResult result = renderer.renderFrame(request);
    for (const TimingRow& row : result.timings.rows) samples.add(row.name, row.milliseconds);
    gpuTotals.push_back(result.timings.gpuTotal());
    run.raysPerPixel = std::stoi(result.decisions.at("shadow_rays"));
    run.transport = result.decisions.at("shadow_transport");
  }
  for (const std::string& name : samples.names()) run.passes.push_back(samples.stats(name));
  run.raysMs = samples.median("shadow rays");
  run.filterMs = samples.median("shadow filter");
  run.frameGpuMs = median(gpuTotals);
  const double rays = static_cast<double>(o.width) * o.height * run.raysPerPixel;
  run.raysPerSecond = run.raysMs > 0.0 ? rays / (run.raysMs / 1000.0) : 0.0;
  return run;
}

// A square grid of `triangles` triangles (rounded to a whole grid), a little wavy so that its
// boxes are not flat, as a binary glTF; `salt` moves it so that each build misses the cache.
std::vector<std::uint8_t> gridGlb(int triangles, int salt) {
  const int side = std::max(1, static_cast<int>(std::sqrt(triangles / 2.0)));
  std::vector<float> positions;
  positions.reserve(static_cast<std::size_t>(side + 1) * (side + 1) * 3);
  for (int z = 0; z <= side; ++z) {
    for (int x = 0; x <= side; ++x) {
      const float u = static_cast<float>(x) / static_cast<float>(side);
      const float v = static_cast<float>(z) / static_cast<float>(side);
      positions.insert(positions.end(), {u * 10.0F,
                                         0.2F * std::sin(u * 40.0F) * std::cos(v * 40.0F) +
                                             0.001F * static_cast<float>(salt),
                                         v * 10.0F});
    }
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(static_cast<std::size_t>(side) * side * 6);
  const auto at = [side](int x, int z) { return static_cast<std::uint32_t>(z * (side + 1) + x); };
  for (int z = 0; z < side; ++z) {
    for (int x = 0; x < side; ++x) {
      indices.insert(indices.end(), {at(x, z), at(x, z + 1), at(x + 1, z), at(x + 1, z),
                                     at(x, z + 1), at(x + 1, z + 1)});
    }
  }
  const std::size_t positionBytes = positions.size() * sizeof(float);
  const std::size_t indexBytes = indices.size() * sizeof(std::uint32_t);
  const json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
      {"buffers", {{{"byteLength", positionBytes + indexBytes}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteLength", positionBytes}},
        {{"buffer", 0}, {"byteOffset", positionBytes}, {"byteLength", indexBytes}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", positions.size() / 3},
         {"type", "VEC3"},
         {"min", {0.0, -0.21 + 0.001 * salt, 0.0}},
         {"max", {10.0, 0.21 + 0.001 * salt, 10.0}}},
        {{"bufferView", 1},
         {"componentType", 5125},
         {"count", indices.size()},
         {"type", "SCALAR"}}}}};
  std::string text = gltf.dump();
  text.resize((text.size() + 3) / 4 * 4, ' ');
  std::vector<std::uint8_t> glb;
  const auto put32 = [&glb](std::size_t value) {
    for (int i = 0; i < 4; ++i) glb.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
  };
  put32(0x46546C67U);
  put32(2);
  put32(12 + 8 + text.size() + 8 + positionBytes + indexBytes);
  put32(text.size());
  put32(0x4E4F534AU);
  glb.insert(glb.end(), text.begin(), text.end());
  put32(positionBytes + indexBytes);
  put32(0x004E4942U);
  const auto* positionData = reinterpret_cast<const std::uint8_t*>(positions.data());
  const auto* indexData = reinterpret_cast<const std::uint8_t*>(indices.data());
  glb.insert(glb.end(), positionData, positionData + positionBytes);
  glb.insert(glb.end(), indexData, indexData + indexBytes);
  return glb;
}

TimingStats buildTimes(Renderer& renderer, const std::vector<RenderRequest>& requests) {
  TimingSamples samples;
  for (const RenderRequest& request : requests) {
    const RenderResult result = renderer.renderFrame(request);
    const double ms = result.timings.get("shadow as build");
    if (ms < 0.0) throw Error(ErrorCode::Internal, "a scene's first frame built no structures");
    samples.add("shadow as build", ms);
  }
  return samples.stats("shadow as build");
}

std::vector<ShadowBuild> runBuilds(const ShadowBenchmarkOptions& o, Renderer& renderer) {
  std::vector<ShadowBuild> builds;
  // The demo: a fresh renderer per build, so that its scene is new to the cache each time.
  {
    TimingSamples samples;
    for (int i = 0; i < o.buildIterations; ++i) {
      Renderer fresh(o.renderer);
      RenderRequest request = parseRenderRequest(
          R"({"settings": {"shadows": "on"}, "output": {"width": 64, "height": 64}})");
      samples.add("shadow as build", fresh.renderFrame(request).timings.get("shadow as build"));
    }
    builds.push_back({"demo", 0, samples.stats("shadow as build")});
  }
  if (o.buildTriangles > 0) {
    std::vector<RenderRequest> requests;
    for (int i = 0; i < o.buildIterations; ++i) {
      RenderRequest request = parseRenderRequest(
          R"({"settings": {"shadows": "on"}, "output": {"width": 64, "height": 64}})");
      request.scene.kind = SceneSource::Kind::InlineGlb;
      request.scene.glbBytes = gridGlb(o.buildTriangles, i + 1);
      request.scene.displayName = "grid";
      requests.push_back(std::move(request));
    }
    const int side = std::max(1, static_cast<int>(std::sqrt(o.buildTriangles / 2.0)));
    builds.push_back({fmt::format("grid of {} triangles", 2 * side * side),
                      static_cast<std::size_t>(2) * side * side, buildTimes(renderer, requests)});
  }
  return builds;
}

std::vector<ShadowTracing> pathsToRun(const ShadowBenchmarkOptions& o, const ShadowInfo& info) {
  if (!o.paths.empty()) return o.paths;
  std::vector<ShadowTracing> paths;
  if (info.rayQuery) paths.push_back(ShadowTracing::RayQuery);
  if (info.rayTracingPipeline) paths.push_back(ShadowTracing::Pipeline);
  return paths;
}

}  // namespace

ShadowBenchmarkResult runShadowBenchmark(const ShadowBenchmarkOptions& options) {
  checkOptions(options);
  Renderer renderer(options.renderer);
  ShadowBenchmarkResult result;
  result.device = renderer.device();
  result.options = options;
  // The first shadowed frame makes the tracer (or says why it cannot).
  renderer.renderFrame(parseRenderRequest(
      R"({"settings": {"shadows": "on"}, "output": {"width": 16, "height": 16}})"));
  result.shadows = renderer.shadowInfo();
  for (ShadowTracing path : pathsToRun(options, result.shadows)) {
    for (int k : options.shadowSamples) {
      result.runs.push_back(runFrames(renderer, options, path, k));
      if (options.progress) options.progress(result.runs.back());
    }
  }
  result.builds = runBuilds(options, renderer);
  return result;
}

}  // namespace lgh::bench
