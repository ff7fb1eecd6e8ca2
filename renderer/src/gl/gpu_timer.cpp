#include "gl/gpu_timer.hpp"

namespace lgh::gl {

GLuint GpuTimer::nextQuery() {
  if (used_ == pool_.size()) pool_.emplace_back(GL_TIMESTAMP);
  return pool_[used_++].id();
}

int GpuTimer::begin(std::string pass) {
  Pass entry{std::move(pass), nextQuery(), 0, open_++, std::chrono::steady_clock::now()};
  glQueryCounter(entry.begin, GL_TIMESTAMP);
  passes_.push_back(std::move(entry));
  return static_cast<int>(passes_.size()) - 1;
}

void GpuTimer::end(int token) {
  Pass& pass = passes_.at(static_cast<size_t>(token));
  pass.end = nextQuery();
  glQueryCounter(pass.end, GL_TIMESTAMP);
  pass.cpuMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - pass.issued)
          .count();
  --open_;
}

void GpuTimer::collect(TimingTable& table) {
  for (const Pass& pass : passes_) {
    if (pass.end == 0) continue;
    GLuint64 begin = 0;
    GLuint64 end = 0;
    glGetQueryObjectui64v(pass.begin, GL_QUERY_RESULT, &begin);
    glGetQueryObjectui64v(pass.end, GL_QUERY_RESULT, &end);
    double ms = end >= begin ? static_cast<double>(end - begin) * 1e-6 : 0.0;
    table.add(pass.name, TimingRow::Clock::Gpu, ms, pass.depth);
    table.rows.back().cpuMilliseconds = pass.cpuMs;
  }
  discard();
}

void GpuTimer::discard() {
  passes_.clear();
  used_ = 0;
  open_ = 0;
}

}  // namespace lgh::gl
