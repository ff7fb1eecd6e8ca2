#include "lgh/task_pool.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <memory>
#include <string>

#include "lgh/thread_name.hpp"

namespace lgh {

int TaskPool::hardwareThreads() {
  // Read once: libstdc++ asks the kernel each time (it opens /sys/devices/system/cpu/online),
  // and the daemon's render thread asks for every frame (its frames-in-flight limit).
  static const int threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return threads;
}

TaskPool::TaskPool(int threads, std::string_view name) : name_(name) {
  const int count = threads < 1 ? hardwareThreads() : threads;
  workers_.reserve(static_cast<std::size_t>(count));
  try {
    for (int i = 0; i < count; ++i) workers_.emplace_back([this, i] { work(i); });
  } catch (...) {  // no thread for the rest: the ones made must be joined before this throws
    stop();
    throw;
  }
}

TaskPool::~TaskPool() { stop(); }

void TaskPool::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  pending_.release(static_cast<std::ptrdiff_t>(workers_.size()));
  for (std::thread& worker : workers_) worker.join();
}

void TaskPool::submit(std::function<void()> task) {
  {
    std::lock_guard lock(mutex_);
    tasks_.push_back(std::move(task));
  }
  pending_.release();
}

int TaskPool::idleWorkers() const {
  std::lock_guard lock(mutex_);
  const int waiting = threads() - running_ - static_cast<int>(tasks_.size());
  return std::max(waiting, 0);
}

void TaskPool::waitIdle() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return tasks_.empty() && running_ == 0; });
}

void TaskPool::work(int index) {
  nameThisThread(name_ + "-" + std::to_string(index));
  for (;;) {
    pending_.acquire();  // a queued task's count, or a stop's
    std::unique_lock lock(mutex_);
    // Each count was given with a task: the queue holds one unless this count is a stop's.
    if (tasks_.empty()) return;  // stopping, and nothing left to run
    std::function<void()> task = std::move(tasks_.front());
    tasks_.pop_front();
    ++running_;
    lock.unlock();
    task();
    lock.lock();
    --running_;
    if (tasks_.empty() && running_ == 0) idle_.notify_all();
  }
}

namespace {

// The indices of one parallelFor, claimed one at a time by the caller and by helper tasks. A
// helper that starts after every index is claimed returns at once.
struct ParallelRange {
  ParallelRange(std::size_t count, const std::function<void(std::size_t)>& body)
      : count(count), body(body) {}

  void runClaimed() {
    for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!error) error = std::current_exception();
      }
      std::lock_guard lock(mutex);
      if (++done == count) finished.notify_all();
    }
  }

  const std::size_t count;
  const std::function<void(std::size_t)>& body;
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::condition_variable finished;
  std::size_t done = 0;
  std::exception_ptr error;
};

}  // namespace

void TaskPool::parallelFor(std::size_t count, const std::function<void(std::size_t)>& body) {
  if (count == 0) return;
  auto range = std::make_shared<ParallelRange>(count, body);
  const auto helpers = std::min<std::size_t>(count - 1, static_cast<std::size_t>(idleWorkers()));
  if (helpers > 0) {
    {
      std::lock_guard lock(mutex_);
      // At the front: a started image finishes before the next one begins.
      for (std::size_t i = 0; i < helpers; ++i) {
        tasks_.emplace_front([range] { range->runClaimed(); });
      }
    }
    pending_.release(static_cast<std::ptrdiff_t>(helpers));
  }
  range->runClaimed();
  std::unique_lock lock(range->mutex);
  range->finished.wait(lock, [&] { return range->done == count; });
  if (range->error) std::rethrow_exception(range->error);
}

}  // namespace lgh
