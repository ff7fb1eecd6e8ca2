// The per-pass GPU timer (gl/gpu_timer.hpp) on the suite's GL context (llvmpipe in CI):
//  - every pass gets its row, in begin order, with its nesting depth and the render thread's
//    issue time;
//  - on a CPU rasteriser a compute pass reads GL's clock instead of timestamp queries, and
//    begins no earlier than the drawing it waited for: a heavy draw's row and the row of the
//    dispatch that samples what it drew add up to no more than the GL time both took, as two
//    rows of one GPU doing one thing after the other must.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "context/gl_context.hpp"
#include "gl/gl_objects.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/software_rasterizer.hpp"
#include "test_support.hpp"

namespace {

constexpr int kSize = 512;

// A full-screen triangle whose fragments each loop a while, so the draw takes tens of ms on a CPU.
constexpr const char* kVertex = R"(#version 450 core
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
})";
constexpr const char* kHeavyFragment = R"(#version 450 core
out vec4 color;
void main() {
  float v = gl_FragCoord.x * 1e-3;
  for (int i = 0; i < 300; ++i) v = fract(sin(v * 12.9898 + float(i)) * 43758.5453);
  color = vec4(v);
})";
// Reads what the draw wrote: its dispatch waits for the drawing.
constexpr const char* kSampling = R"(#version 450 core
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D drawn;
layout(std430, binding = 0) writeonly buffer Sums { float sums[]; };
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  sums[p.y * 512 + p.x] = texelFetch(drawn, p, 0).r;
})";

GLuint compile(GLenum type, const char* source) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  EXPECT_EQ(ok, GL_TRUE);
  return shader;
}

lgh::gl::Program link(std::initializer_list<std::pair<GLenum, const char*>> stages) {
  lgh::gl::Program program;
  for (const auto& [type, source] : stages) {
    const GLuint shader = compile(type, source);
    glAttachShader(program.id(), shader);
    glDeleteShader(shader);
  }
  glLinkProgram(program.id());
  GLint ok = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  EXPECT_EQ(ok, GL_TRUE);
  return program;
}

GLint64 glClock() {
  GLint64 now = 0;
  glGetInteger64v(GL_TIMESTAMP, &now);
  return now;
}

class GpuTimerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context = lgh::GlContext::create(lgh::test::rendererOptions()); }
  static void TearDownTestSuite() { context.reset(); }
  static inline std::unique_ptr<lgh::GlContext> context;
};

TEST_F(GpuTimerTest, RowsComeInBeginOrderWithTheirDepth) {
  lgh::gl::GpuTimer timer;
  {
    lgh::gl::ScopedGpuPass outer(timer, "outer");
    { lgh::gl::ScopedGpuPass inner(timer, "inner", lgh::gl::GpuWork::Compute); }
  }
  { lgh::gl::ScopedGpuPass last(timer, "last"); }
  lgh::TimingTable table;
  timer.collect(table);
  ASSERT_EQ(table.rows.size(), 3U);
  EXPECT_EQ(table.rows[0].name, "outer");
  EXPECT_EQ(table.rows[1].name, "inner");
  EXPECT_EQ(table.rows[2].name, "last");
  EXPECT_EQ(table.rows[0].depth, 0);
  EXPECT_EQ(table.rows[1].depth, 1);
  EXPECT_EQ(table.rows[2].depth, 0);
  for (const lgh::TimingRow& row : table.rows) {
    EXPECT_EQ(row.clock, lgh::TimingRow::Clock::Gpu);
    EXPECT_GE(row.milliseconds, 0.0);
    EXPECT_GE(row.cpuMilliseconds, 0.0);
  }
}

TEST_F(GpuTimerTest, ADispatchAfterADrawItSamplesIsTimedFromTheDrawsEnd) {
  if (!lgh::gl::softwareRasterizer()) GTEST_SKIP() << "compute passes read queries on a GPU";
  lgh::gl::Texture target(GL_TEXTURE_2D);
  glTextureStorage2D(target.id(), 1, GL_R32F, kSize, kSize);
  lgh::gl::Framebuffer framebuffer;
  glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
  lgh::gl::Buffer sums;
  glNamedBufferStorage(sums.id(), GLsizeiptr{kSize} * kSize * 4, nullptr, 0);
  lgh::gl::VertexArray vertices;
  const lgh::gl::Program heavy =
      link({{GL_VERTEX_SHADER, kVertex}, {GL_FRAGMENT_SHADER, kHeavyFragment}});
  const lgh::gl::Program sampling = link({{GL_COMPUTE_SHADER, kSampling}});

  glFinish();
  const GLint64 start = glClock();
  lgh::gl::GpuTimer timer;
  {
    lgh::gl::ScopedGpuPass pass(timer, "draw");
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    glViewport(0, 0, kSize, kSize);
    glUseProgram(heavy.id());
    glBindVertexArray(vertices.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  {
    lgh::gl::ScopedGpuPass pass(timer, "dispatch", lgh::gl::GpuWork::Compute);
    glUseProgram(sampling.id());
    glBindTextureUnit(0, target.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, sums.id());
    glDispatchCompute(kSize / 8, kSize / 8, 1);
  }
  glFinish();
  const double spanMs = static_cast<double>(glClock() - start) * 1e-6;
  lgh::TimingTable table;
  timer.collect(table);
  ASSERT_EQ(table.rows.size(), 2U);
  const double drawMs = table.rows[0].milliseconds;
  const double dispatchMs = table.rows[1].milliseconds;
  EXPECT_GT(drawMs, 5.0) << "the draw is meant to be heavy";
  EXPECT_GT(dispatchMs, 0.0);
  // Had the dispatch's row begun where its call did, it would hold the draw's time as well.
  EXPECT_LE(drawMs + dispatchMs, spanMs + 0.5) << drawMs << " + " << dispatchMs << " ms";
}

}  // namespace
