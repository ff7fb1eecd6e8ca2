// Per-pass GPU timing with GL_TIMESTAMP queries (glQueryCounter), so passes may nest: only one
// GL_TIME_ELAPSED query can be active at a time. Results are read after the frame, once. Each
// pass also gets the render thread's time between its two queries: what issuing it cost the CPU.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "gl/gl_objects.hpp"
#include "lgh/timing.hpp"

namespace lgh::gl {

class GpuTimer {
 public:
  // Returns a token for end().
  int begin(std::string pass);
  void end(int token);
  // Waits for the results and appends one Gpu row per pass, in begin order. Resets the timer.
  void collect(TimingTable& table);
  // Drops recorded passes without reading them (after a failed frame).
  void discard();

 private:
  GLuint nextQuery();
  struct Pass {
    std::string name;
    GLuint begin = 0;
    GLuint end = 0;
    int depth = 0;  // passes open when it began
    std::chrono::steady_clock::time_point issued;
    double cpuMs = 0.0;
  };
  std::vector<Query> pool_;
  std::size_t used_ = 0;
  std::vector<Pass> passes_;
  int open_ = 0;
};

// Brackets a scope: ScopedGpuPass pass(timer, "gbuffer");
class ScopedGpuPass {
 public:
  ScopedGpuPass(GpuTimer& timer, std::string name)
      : timer_(timer), token_(timer.begin(std::move(name))) {}
  ~ScopedGpuPass() { timer_.end(token_); }
  ScopedGpuPass(const ScopedGpuPass&) = delete;
  ScopedGpuPass& operator=(const ScopedGpuPass&) = delete;

 private:
  GpuTimer& timer_;
  int token_;
};

}  // namespace lgh::gl
