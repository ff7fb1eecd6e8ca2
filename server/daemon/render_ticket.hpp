// One render's outcome, settled exactly once: by the render thread when the render finishes, or
// earlier by its waiter (deadline) or by the shutdown (cancelled). Whoever settles first wins; a
// later result is discarded, which is how a render that ran past its deadline is answered 504
// without disturbing the render thread.
#pragma once

#include <condition_variable>
#include <mutex>
#include <optional>

#include "api_error.hpp"
#include "clock.hpp"
#include "lgh/renderer.hpp"

namespace lghd {

class RenderTicket {
 public:
  explicit RenderTicket(lgh::RenderRequest request) : request_(std::move(request)) {}

  const lgh::RenderRequest& request() const { return request_; }

  // Each returns whether it settled the ticket (false: it was settled already).
  bool complete(lgh::RenderResult result);
  bool fail(ApiError error);
  bool settled() const;

  // Blocks until the ticket is settled or `deadline` passes; at the deadline it settles itself
  // with a 504. Returns the result (moved out: call once) or throws the ApiError.
  lgh::RenderResult wait(Clock::time_point deadline);

  // The render worker `gpu` (its place in --gpus) has started it.
  void markStarted(int gpu);
  // When the render thread started it; empty while it waits in the queue.
  std::optional<Clock::time_point> started() const;
  // The worker that rendered it (-1: none yet).
  int gpu() const;

 private:
  bool settle(std::optional<lgh::RenderResult> result, std::optional<ApiError> error);

  lgh::RenderRequest request_;
  mutable std::mutex mutex_;
  std::condition_variable settledCondition_;
  bool settled_ = false;
  std::optional<lgh::RenderResult> result_;
  std::optional<ApiError> error_;
  std::optional<Clock::time_point> started_;
  int gpu_ = -1;
};

}  // namespace lghd
