#include "lgh/bench/scene_load_benchmark.hpp"

#include <fstream>
#include <sstream>

#include "core/stopwatch.hpp"
#include "lgh/bench/statistics.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/worker/scene_worker.hpp"

namespace lgh::bench {
namespace {

std::size_t sceneBytes(const Scene& scene) {
  std::size_t bytes = 0;
  for (const Mesh& mesh : scene.meshes) {
    for (const Primitive& primitive : mesh.primitives) {
      bytes += primitive.vertices.size() * sizeof(Vertex) +
               primitive.indices.size() * sizeof(std::uint32_t);
    }
  }
  for (const Image8& image : scene.images) bytes += image.pixels.size();
  return bytes;
}

// Memory the process holds for itself (private pages; libraries it shares with the daemon
// excluded), from /proc/PID/smaps_rollup.
double privateMb(pid_t pid) {
  std::ifstream rollup("/proc/" + std::to_string(pid) + "/smaps_rollup");
  std::string line;
  double kb = 0.0;
  while (std::getline(rollup, line)) {
    if (line.rfind("Private_Clean:", 0) == 0 || line.rfind("Private_Dirty:", 0) == 0) {
      std::istringstream fields(line.substr(line.find(':') + 1));
      double value = 0.0;
      fields >> value;
      kb += value;
    }
  }
  return kb / 1024.0;
}

}  // namespace

SceneLoadBenchmarkResult runSceneLoadBenchmark(const SceneLoadBenchmarkConfig& config) {
  SceneWorkerOptions options;
  options.executable = config.workerExecutable;
  options.arguments = config.workerArguments;
  SceneLoadBenchmarkResult result;
  std::vector<double> starts;
  for (int i = 0; i < config.repeat; ++i) {
    const Stopwatch start;
    worker::SceneWorker fresh(options);
    starts.push_back(start.elapsedMs());
    if (i == 0) result.workerIdlePrivateMb = privateMb(fresh.pid());
  }
  result.workerStartMs = median(starts);
  worker::SceneWorker worker(options);
  for (const std::filesystem::path& asset : config.assets) {
    SceneSource source;
    source.kind = SceneSource::Kind::AssetPath;
    source.assetPath = asset.filename().string();
    source.displayName = source.assetPath;
    const worker::LoadJob job{source, asset.parent_path(), SceneLoadLimits{}, SceneLoadOptions{}};
    SceneLoadRow row;
    row.asset = source.assetPath;
    std::vector<double> inProcess;
    std::vector<double> inWorker;
    for (int i = 0; i < config.repeat; ++i) {
      const Stopwatch here;
      const Scene scene = loadSceneSource(job.source, job.assetRoot, job.limits);
      inProcess.push_back(here.elapsedMs());
      row.triangles = scene.triangleCount();
      row.sceneBytes = sceneBytes(scene);
      const Stopwatch there;
      const Scene loaded = worker.load(job);
      inWorker.push_back(there.elapsedMs());
    }
    row.inProcessMs = median(inProcess);
    row.workerMs = median(inWorker);
    result.rows.push_back(row);
  }
  return result;
}

}  // namespace lgh::bench
