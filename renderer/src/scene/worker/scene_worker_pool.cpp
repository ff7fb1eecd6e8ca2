#include "scene/worker/scene_worker_pool.hpp"

#include "scene/scene.hpp"
#include "scene/worker/scene_worker.hpp"

namespace lgh::worker {

SceneWorkerPool::SceneWorkerPool(SceneWorkerOptions options) : options_(std::move(options)) {
  workers_.push_back(std::make_unique<SceneWorker>(options_));
  idle_.push_back(workers_.back().get());
}

SceneWorkerPool::~SceneWorkerPool() = default;

SceneWorker& SceneWorkerPool::acquire() {
  std::unique_lock lock(mutex_);
  if (idle_.empty() && workers_.size() + starting_ < maxProcesses()) {
    // Its start-up (about 0.2 s) happens outside the lock, so that the others stay usable.
    ++starting_;
    lock.unlock();
    std::unique_ptr<SceneWorker> started;
    try {
      started = std::make_unique<SceneWorker>(options_);
    } catch (...) {
      lock.lock();
      --starting_;
      throw;
    }
    lock.lock();
    --starting_;
    workers_.push_back(std::move(started));
    return *workers_.back();
  }
  const std::uint64_t turn = nextTicket_++;
  freed_.wait(lock, [&] { return !idle_.empty() && turn == serving_; });
  ++serving_;
  SceneWorker* worker = idle_.back();
  idle_.pop_back();
  lock.unlock();
  freed_.notify_all();  // the next turn may find another idle worker
  return *worker;
}

void SceneWorkerPool::release(SceneWorker& worker) {
  {
    const std::lock_guard lock(mutex_);
    idle_.push_back(&worker);
  }
  freed_.notify_all();  // the waiter whose turn it is
}

Scene SceneWorkerPool::load(const LoadJob& job) {
  SceneWorker& worker = acquire();
  try {
    Scene scene = worker.load(job);
    release(worker);
    return scene;
  } catch (...) {
    release(worker);
    throw;
  }
}

}  // namespace lgh::worker
