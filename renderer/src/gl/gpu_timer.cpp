#include "gl/gpu_timer.hpp"

#include <algorithm>

#include "gl/software_rasterizer.hpp"

namespace lgh::gl {
namespace {

GLint64 glClock() {
  GLint64 now = 0;
  glGetInteger64v(GL_TIMESTAMP, &now);
  return now;
}

}  // namespace

GLuint GpuTimer::nextQuery() {
  if (used_ == pool_.size()) pool_.emplace_back(GL_TIMESTAMP);
  return pool_[used_++].id();
}

bool GpuTimer::readsClock(GpuWork work) {
  if (work != GpuWork::Compute) return false;
  if (!synchronousCompute_) synchronousCompute_ = softwareRasterizer();
  return *synchronousCompute_;
}

int GpuTimer::begin(std::string pass, GpuWork work) {
  Pass entry;
  entry.name = std::move(pass);
  entry.depth = open_++;
  entry.passesEnded = endOrder_.size();
  entry.issued = std::chrono::steady_clock::now();
  entry.clocked = readsClock(work);
  if (entry.clocked) {
    entry.beginClock = glClock();
  } else {
    entry.begin = nextQuery();
    glQueryCounter(entry.begin, GL_TIMESTAMP);
  }
  passes_.push_back(std::move(entry));
  return static_cast<int>(passes_.size()) - 1;
}

void GpuTimer::end(int token) {
  Pass& pass = passes_.at(static_cast<size_t>(token));
  if (pass.clocked) {
    pass.endClock = glClock();
  } else {
    pass.end = nextQuery();
    glQueryCounter(pass.end, GL_TIMESTAMP);
  }
  pass.ended = true;
  endOrder_.push_back(static_cast<std::size_t>(token));
  pass.cpuMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - pass.issued)
          .count();
  --open_;
}

void GpuTimer::collect(TimingTable& table) {
  // Each pass's GL times: from its queries, or from GL's clock.
  std::vector<GLint64> begins(passes_.size(), 0);
  std::vector<GLint64> ends(passes_.size(), 0);
  for (std::size_t i = 0; i < passes_.size(); ++i) {
    const Pass& pass = passes_[i];
    if (!pass.ended) continue;
    if (pass.clocked) {
      begins[i] = pass.beginClock;
      ends[i] = pass.endClock;
      continue;
    }
    GLuint64 begin = 0;
    GLuint64 end = 0;
    glGetQueryObjectui64v(pass.begin, GL_QUERY_RESULT, &begin);
    glGetQueryObjectui64v(pass.end, GL_QUERY_RESULT, &end);
    begins[i] = static_cast<GLint64>(begin);
    ends[i] = static_cast<GLint64>(end);
  }
  for (std::size_t i = 0; i < passes_.size(); ++i) {
    const Pass& pass = passes_[i];
    if (!pass.ended) continue;
    GLint64 begin = begins[i];
    if (pass.clocked) {
      // Its dispatch waited for the drawing of the passes that ended before it began.
      for (std::size_t e = 0; e < pass.passesEnded; ++e) {
        begin = std::max(begin, ends[endOrder_[e]]);
      }
    }
    const double ms = ends[i] >= begin ? static_cast<double>(ends[i] - begin) * 1e-6 : 0.0;
    table.add(pass.name, TimingRow::Clock::Gpu, ms, pass.depth);
    table.rows.back().cpuMilliseconds = pass.cpuMs;
  }
  discard();
}

void GpuTimer::discard() {
  passes_.clear();
  endOrder_.clear();
  used_ = 0;
  open_ = 0;
}

}  // namespace lgh::gl
