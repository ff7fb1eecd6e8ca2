#include "render_ticket.hpp"

namespace lghd {

bool RenderTicket::settle(std::optional<lgh::RenderResult> result, std::optional<ApiError> error) {
  {
    std::lock_guard lock(mutex_);
    if (settled_) return false;
    settled_ = true;
    result_ = std::move(result);
    error_ = std::move(error);
  }
  settledCondition_.notify_all();
  return true;
}

bool RenderTicket::complete(lgh::RenderResult result) {
  return settle(std::move(result), std::nullopt);
}

bool RenderTicket::fail(ApiError error) { return settle(std::nullopt, std::move(error)); }

bool RenderTicket::settled() const {
  std::lock_guard lock(mutex_);
  return settled_;
}

void RenderTicket::markStarted(int gpu) {
  std::lock_guard lock(mutex_);
  started_ = Clock::now();
  gpu_ = gpu;
}

int RenderTicket::gpu() const {
  std::lock_guard lock(mutex_);
  return gpu_;
}

std::optional<Clock::time_point> RenderTicket::started() const {
  std::lock_guard lock(mutex_);
  return started_;
}

lgh::RenderResult RenderTicket::wait(Clock::time_point deadline) {
  std::unique_lock lock(mutex_);
  if (!settledCondition_.wait_until(lock, deadline, [this] { return settled_; })) {
    settled_ = true;
    error_ = timedOut(started_ ? "the render ran past its deadline"
                               : "the render waited in the queue past its deadline");
  }
  if (error_) throw *error_;
  return std::move(*result_);
}

}  // namespace lghd
