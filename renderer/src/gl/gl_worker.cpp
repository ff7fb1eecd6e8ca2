#include "gl/gl_worker.hpp"

#include <spdlog/spdlog.h>

#include "lgh/error.hpp"
#include "lgh/thread_name.hpp"

namespace lgh::gl {

Worker::Worker(std::unique_ptr<GlContext> context, const Api* renderApi)
    : context_(std::move(context)), renderApi_(renderApi) {
  // Shared with the thread, which may still be inside set_value() when this constructor returns.
  auto started = std::make_shared<std::promise<void>>();
  auto ready = started->get_future();
  thread_ = std::thread([this, started] { loop(*started); });
  try {
    ready.get();
  } catch (...) {
    thread_.join();
    throw;
  }
}

Worker::~Worker() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
}

bool Worker::sharesCurrentContext() const {
  const Api* current = currentApi();
  return current != nullptr && (current == renderApi_ || current == &context_->api());
}

void Worker::enqueue(std::packaged_task<void()> task) {
  {
    const std::lock_guard lock(mutex_);
    tasks_.push_back(std::move(task));
  }
  wake_.notify_one();
}

void Worker::logFailure(const char* what) { spdlog::error("GL worker: a task failed: {}", what); }

void Worker::loop(std::promise<void>& started) {
  nameThisThread("lgh-gl-worker");
  try {
    context_->makeCurrent();
  } catch (...) {
    started.set_exception(std::current_exception());
    return;
  }
  started.set_value();
  for (;;) {
    std::packaged_task<void()> task;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || !tasks_.empty(); });
      if (tasks_.empty()) break;
      task = std::move(tasks_.front());
      tasks_.pop_front();
    }
    task();  // a task's exception goes to its future; posted tasks log their own
  }
  context_->doneCurrent();
}

}  // namespace lgh::gl
