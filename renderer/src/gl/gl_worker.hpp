// A thread with a GL context of its own in the renderer's share group (GlContext::createShared):
// the scene cache uploads scenes parsed ahead and frees evicted ones there, off the render
// thread. Tasks run one at a time, in the order given. Objects that are not shared (vertex
// arrays, framebuffers, queries) must not be made or deleted by its tasks.
#pragma once

#include <condition_variable>
#include <deque>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>

#include "context/gl_context.hpp"

namespace lgh::gl {

class Worker {
 public:
  // Starts the thread and makes `context` current on it. `renderApi`: the functions of the
  // context that `context` shares with (the render thread's). Throws lgh::Error(Unavailable)
  // when the context cannot be made current there.
  Worker(std::unique_ptr<GlContext> context, const Api* renderApi);
  // Runs what is queued, then ends the thread (which releases its context).
  ~Worker();
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Runs `task` on the worker; its result, or its exception, comes through the future.
  template <typename Task>
  auto run(Task task) -> std::future<std::invoke_result_t<Task&>> {
    std::packaged_task<std::invoke_result_t<Task&>()> packaged(std::move(task));
    auto result = packaged.get_future();
    enqueue(std::packaged_task<void()>([packaged = std::move(packaged)]() mutable { packaged(); }));
    return result;
  }
  // Runs `task` on the worker some time later; what it throws is logged.
  template <typename Task>
  void post(Task task) {
    enqueue(std::packaged_task<void()>([task = std::move(task)]() mutable {
      try {
        task();
      } catch (const std::exception& error) {
        logFailure(error.what());
      }
    }));
  }
  // Whether GL objects of the share group may be deleted on the calling thread: its current
  // context is the worker's or the render thread's.
  bool sharesCurrentContext() const;
  const DeviceInfo& info() const { return context_->info(); }

 private:
  void enqueue(std::packaged_task<void()> task);
  static void logFailure(const char* what);
  void loop(std::promise<void>& started);

  std::unique_ptr<GlContext> context_;
  const Api* renderApi_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::packaged_task<void()>> tasks_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace lgh::gl
