#include "scene/worker/scene_worker_pool.hpp"

#include "scene/scene.hpp"
#include "scene/worker/scene_worker.hpp"

namespace lgh::worker {

SceneWorkerPool::SceneWorkerPool(SceneWorkerOptions options) : options_(std::move(options)) {
  workers_.push_back(std::make_unique<SceneWorker>(options_));
  idle_.push_back(workers_.back().get());
}

SceneWorkerPool::~SceneWorkerPool() = default;

SceneWorkerPool::Turn SceneWorkerPool::reserveTurn() {
  const std::lock_guard lock(mutex_);
  return {this, nextTicket_++};
}

void SceneWorkerPool::advance() {
  ++serving_;
  while (dropped_.erase(serving_) > 0) ++serving_;
}

bool SceneWorkerPool::servable(std::uint64_t number) const {
  return number == serving_ && (!idle_.empty() || workers_.size() + starting_ < maxProcesses());
}

void SceneWorkerPool::wakeServing() {
  if (const auto waiter = waiting_.find(serving_); waiter != waiting_.end()) {
    waiter->second->notify_one();
  }
}

void SceneWorkerPool::drop(std::uint64_t number) {
  const std::lock_guard lock(mutex_);
  if (number == serving_) {
    advance();
  } else {
    dropped_.insert(number);
  }
  wakeServing();
}

SceneWorker& SceneWorkerPool::acquire(Turn turn) {
  const std::uint64_t number = turn.number_;
  turn.pool_ = nullptr;  // used here, not dropped
  std::unique_lock lock(mutex_);
  if (!servable(number)) {
    std::condition_variable mine;
    waiting_.emplace(number, &mine);
    mine.wait(lock, [&] { return servable(number); });
    waiting_.erase(number);
  }
  advance();
  if (!idle_.empty()) {
    SceneWorker* worker = idle_.back();
    idle_.pop_back();
    wakeServing();  // the next turn may find another idle worker
    return *worker;
  }
  // Every worker is busy and there is room for one more: its start-up (about 0.2 s) happens
  // outside the lock, so that the others stay usable and the next turns go on.
  ++starting_;
  wakeServing();
  lock.unlock();
  std::unique_ptr<SceneWorker> started;
  try {
    started = std::make_unique<SceneWorker>(options_);
  } catch (...) {
    lock.lock();
    --starting_;
    wakeServing();
    throw;
  }
  lock.lock();
  --starting_;
  workers_.push_back(std::move(started));
  return *workers_.back();
}

void SceneWorkerPool::release(SceneWorker& worker) {
  const std::lock_guard lock(mutex_);
  idle_.push_back(&worker);
  wakeServing();
}

Scene SceneWorkerPool::load(const LoadJob& job) { return load(job, reserveTurn()); }

Scene SceneWorkerPool::load(const LoadJob& job, Turn turn) {
  SceneWorker& worker = acquire(std::move(turn));
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
