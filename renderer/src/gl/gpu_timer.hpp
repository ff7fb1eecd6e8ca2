// Per-pass GPU timing with GL_TIMESTAMP queries (glQueryCounter), so passes may nest: only one
// GL_TIME_ELAPSED query can be active at a time. Results are read after the frame, once. Each
// pass also gets the render thread's time between its two queries: what issuing it cost the CPU.
//
// On a CPU rasteriser (gl::softwareRasterizer) a pass of compute dispatches (GpuWork::Compute)
// reads GL's clock (glGetInteger64v(GL_TIMESTAMP), the clock the queries read) before and after
// instead: Mesa's llvmpipe runs a dispatch before glDispatchCompute returns, while each timestamp
// query there starts a scene of its own, binned into every tile and woken up on both rasteriser
// threads (5 % of the VM's thumbnail rate: docs/BENCHMARKS.md). Such a pass begins no earlier than
// the query-timed passes that ended before it (the dispatch waits for their drawing).
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "gl/gl_objects.hpp"
#include "lgh/timing.hpp"

namespace lgh::gl {

// What a timed pass issues: draws (or anything), or compute dispatches and copies only (buffer
// clears, texture reads into buffers), which Mesa's CPU rasterisers carry out before returning.
enum class GpuWork { Any, Compute };

class GpuTimer {
 public:
  // Returns a token for end().
  int begin(std::string pass, GpuWork work = GpuWork::Any);
  void end(int token);
  // Waits for the results and appends one Gpu row per pass, in begin order. Resets the timer.
  void collect(TimingTable& table);
  // Drops recorded passes without reading them (after a failed frame).
  void discard();

 private:
  GLuint nextQuery();
  bool readsClock(GpuWork work);
  struct Pass {
    std::string name;
    GLuint begin = 0;  // queries; 0 where the pass read GL's clock
    GLuint end = 0;
    GLint64 beginClock = 0;  // GL's clock, where the pass reads it
    GLint64 endClock = 0;
    bool clocked = false;
    bool ended = false;
    int depth = 0;                // passes open when it began
    std::size_t passesEnded = 0;  // passes that had ended when it began
    std::chrono::steady_clock::time_point issued;
    double cpuMs = 0.0;
  };
  std::vector<Query> pool_;
  std::size_t used_ = 0;
  std::vector<Pass> passes_;
  std::vector<std::size_t> endOrder_;  // tokens in the order their passes ended
  int open_ = 0;
  std::optional<bool> synchronousCompute_;  // the context runs dispatches as they are issued
};

// Brackets a scope: ScopedGpuPass pass(timer, "gbuffer");
class ScopedGpuPass {
 public:
  ScopedGpuPass(GpuTimer& timer, std::string name, GpuWork work = GpuWork::Any)
      : timer_(timer), token_(timer.begin(std::move(name), work)) {}
  ~ScopedGpuPass() { timer_.end(token_); }
  ScopedGpuPass(const ScopedGpuPass&) = delete;
  ScopedGpuPass& operator=(const ScopedGpuPass&) = delete;

 private:
  GpuTimer& timer_;
  int token_;
};

}  // namespace lgh::gl
