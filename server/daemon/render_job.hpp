// A job of the render queue (one render, or a thumbnail batch) and the part of it one render
// worker takes. The front queue (render_queue.hpp) may split a batch's tickets over several
// workers; the waiter still waits on the job's tickets in their order, so a split batch is merged
// back simply by waiting on them one after the other.
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "clock.hpp"
#include "render_ticket.hpp"

namespace lghd {

struct RenderJob {
  std::string requestId;
  std::vector<std::shared_ptr<RenderTicket>> tickets;
  Clock::time_point enqueued;
  Clock::time_point startDeadline;
  std::atomic<bool> cancelled{false};  // the client went away: skip what has not started
  // Pieces still waiting in a worker's queue: the job holds one slot of --queue-depth until the
  // last of them is taken.
  std::atomic<std::size_t> piecesWaiting{0};
};

// The tickets of one job that one worker renders, in the job's order.
struct JobPiece {
  std::shared_ptr<RenderJob> job;
  std::size_t worker = 0;            // the render worker it goes to
  std::vector<std::size_t> tickets;  // indices into job->tickets
  std::vector<std::string> scenes;   // each ticket's scene key (render_scheduler.hpp)
  std::vector<double> estimates;     // each ticket's estimated seconds on this worker
};

}  // namespace lghd
