// Several scene parser workers (scene_worker.hpp) for one renderer, so that the scenes a render
// thread will draw next parse side by side, each in a process of its own. The first worker starts
// with the pool; more start when every running one is busy, up to SceneWorkerOptions::processes.
// A load takes an idle worker, or waits for one: loads are served in the order of their turns,
// taken when the load is asked for (Turn: the look-ahead takes them in the order the scenes are
// drawn, before the prefetch threads that run the loads reach the pool in whatever order).
// With a Turn or without, a load waits for every earlier turn to have been served or dropped.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <set>
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

  // A place in the order loads are served. One that is dropped unused lets the next turn go.
  class Turn {
   public:
    Turn(Turn&& other) noexcept : pool_(other.pool_), number_(other.number_) {
      other.pool_ = nullptr;
    }
    Turn& operator=(Turn&&) = delete;
    Turn(const Turn&) = delete;
    Turn& operator=(const Turn&) = delete;
    ~Turn() {
      if (pool_ != nullptr) pool_->drop(number_);
    }

   private:
    friend class SceneWorkerPool;
    Turn(SceneWorkerPool* pool, std::uint64_t number) : pool_(pool), number_(number) {}
    SceneWorkerPool* pool_;
    std::uint64_t number_;
  };
  // Must not outlive the pool.
  Turn reserveTurn();

  // As SceneWorker::load, on whichever worker is free: with a turn taken now, or with `turn`.
  Scene load(const LoadJob& job);
  Scene load(const LoadJob& job, Turn turn);

  std::size_t maxProcesses() const { return std::max<std::size_t>(options_.processes, 1); }

 private:
  SceneWorker& acquire(Turn turn);
  void release(SceneWorker& worker);
  void drop(std::uint64_t number);
  // Under mutex_: the next turn that was not dropped.
  void advance();
  // Under mutex_: whether turn `number` may take a worker (or start one) now.
  bool servable(std::uint64_t number) const;
  // Under mutex_: wakes the load waiting with the turn being served, if one is. Only that one:
  // waking every waiter (up to one per prefetch thread, 65) at each change cost as many context
  // switches per load.
  void wakeServing();

  SceneWorkerOptions options_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<SceneWorker>> workers_;
  std::vector<SceneWorker*> idle_;
  std::size_t starting_ = 0;         // workers being started outside the lock
  std::uint64_t nextTicket_ = 0;     // the next turn's number
  std::uint64_t serving_ = 0;        // the turn that gets the next idle worker (or starts one)
  std::set<std::uint64_t> dropped_;  // turns after serving_ dropped unused
  // The loads waiting for their turn, by turn: each on a condition of its own.
  std::map<std::uint64_t, std::condition_variable*> waiting_;
};

}  // namespace lgh::worker
