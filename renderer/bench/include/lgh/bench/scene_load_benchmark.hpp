// Scene loading in this process versus in the scene parser worker process (lgh/scene_worker.hpp):
// the cost of parsing untrusted assets out of the daemon's process, per asset, as medians over
// repeated cold loads; plus the worker's start-up time and its memory when idle.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace lgh::bench {

struct SceneLoadBenchmarkConfig {
  std::vector<std::filesystem::path> assets;  // .gltf or .glb files
  int repeat = 10;
  // The worker: this executable started with these arguments (it must call
  // lgh::runSceneParserWorker on file descriptor 3).
  std::filesystem::path workerExecutable;
  std::vector<std::string> workerArguments;
};

struct SceneLoadRow {
  std::string asset;
  std::size_t triangles = 0;
  std::size_t sceneBytes = 0;  // vertices, indices and decoded images
  double inProcessMs = 0.0;    // medians
  double workerMs = 0.0;
};

struct SceneLoadBenchmarkResult {
  std::vector<SceneLoadRow> rows;
  double workerStartMs = 0.0;        // median, spawn until ready
  double workerIdlePrivateMb = 0.0;  // its own pages, not the libraries it shares
};

// Throws lgh::Error when an asset does not load.
SceneLoadBenchmarkResult runSceneLoadBenchmark(const SceneLoadBenchmarkConfig& config);

}  // namespace lgh::bench
