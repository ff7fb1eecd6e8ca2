// A fixed set of worker threads for CPU work beside the render thread: lghd and lgh-render encode
// frames on one (--encode-threads), and the PNG encoder spreads a large image's deflate strips over
// its idle workers. parallelFor() runs on the calling thread too, so a task may call it without
// waiting on itself: a busy pool degrades to serial work, never to a deadlock.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <semaphore>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace lgh {

class TaskPool {
 public:
  // `threads` < 1 means one per hardware thread. Worker i is named "<name>-<i>"
  // (lgh/thread_name.hpp).
  explicit TaskPool(int threads, std::string_view name = "lgh-pool");
  // Runs what is queued, then joins the workers.
  ~TaskPool();
  TaskPool(const TaskPool&) = delete;
  TaskPool& operator=(const TaskPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()); }
  // Queues `task`; a task must not throw (wrap it: nobody would see the exception).
  void submit(std::function<void()> task);
  // Runs body(0) .. body(count - 1) on the calling thread and on workers that are idle now;
  // returns when all have run. The first exception a body throws is rethrown here.
  void parallelFor(std::size_t count, const std::function<void(std::size_t)>& body);
  // Workers waiting for work at this moment (a hint: it may change at once).
  int idleWorkers() const;
  // Blocks until no task is queued or running.
  void waitIdle();

  // One per hardware thread (at least 1).
  static int hardwareThreads();

 private:
  void work(int index);
  void stop();  // runs what is queued, joins the workers

  mutable std::mutex mutex_;
  // One count per queued task and, at stop, one per worker. Workers sleep on this instead of a
  // condition variable: glibc 2.36's pthread_cond_signal can wait for threads it woke before to
  // run, and the render thread, which hands every frame to the encoders, slept there about every
  // other thumbnail (docs/BENCHMARKS.md, "GPU targets, eleventh round").
  std::counting_semaphore<> pending_{0};
  std::condition_variable idle_;
  std::deque<std::function<void()>> tasks_;
  int running_ = 0;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
  std::string name_;
};

}  // namespace lgh
