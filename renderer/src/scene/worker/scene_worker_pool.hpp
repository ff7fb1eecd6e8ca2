// Several scene parser workers (scene_worker.hpp) for one renderer, so that the scenes a render
// thread will draw next parse side by side, each in a process of its own. The first worker starts
// with the pool; more start when every running one is busy, up to SceneWorkerOptions::processes.
// A load takes an idle worker, or waits for one: loads that wait are served in the order they
// came (the look-ahead hints the scenes in the order they are drawn).
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "lgh/renderer_options.hpp"
#include "scene/worker/scene_wire.hpp"

namespace lgh::worker {

class SceneWorker;

class SceneWorkerPool {
 public:
  explicit SceneWorkerPool(SceneWorkerOptions options);
  ~SceneWorkerPool();
  SceneWorkerPool(const SceneWorkerPool&) = delete;
  SceneWorkerPool& operator=(const SceneWorkerPool&) = delete;

  // As SceneWorker::load, on whichever worker is free.
  Scene load(const LoadJob& job);

  std::size_t maxProcesses() const { return std::max<std::size_t>(options_.processes, 1); }

 private:
  SceneWorker& acquire();
  void release(SceneWorker& worker);

  SceneWorkerOptions options_;
  std::mutex mutex_;
  std::condition_variable freed_;
  std::vector<std::unique_ptr<SceneWorker>> workers_;
  std::vector<SceneWorker*> idle_;
  std::size_t starting_ = 0;      // workers being started outside the lock
  std::uint64_t nextTicket_ = 0;  // loads that waited for a worker: the next one's turn number
  std::uint64_t serving_ = 0;     // the turn of the waiting load that gets the next idle worker
};

}  // namespace lgh::worker
