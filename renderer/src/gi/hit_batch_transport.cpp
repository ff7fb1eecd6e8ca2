#include "gi/hit_batch_transport.hpp"

#include <unistd.h>

#include <array>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/stopwatch.hpp"
#include "gl/gl_api.hpp"
#include "lgh/error.hpp"

namespace lgh {
namespace {

void clearGlErrors() {
  while (glGetError() != GL_NO_ERROR) {
  }
}

// Imports one Vulkan buffer's memory into a GL buffer. GL owns the fd once the import succeeds.
bool importBuffer(const vk::SharedBuffer& shared, gl::MemoryObject& memory, gl::Buffer& buffer,
                  std::string& failure) {
  clearGlErrors();
  memory = gl::MemoryObject();
  if (shared.dedicated) {
    const GLint dedicated = GL_TRUE;
    glMemoryObjectParameterivEXT(memory.id(), GL_DEDICATED_MEMORY_OBJECT_EXT, &dedicated);
  }
  glImportMemoryFdEXT(memory.id(), shared.allocationSize, GL_HANDLE_TYPE_OPAQUE_FD_EXT, shared.fd);
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
    close(shared.fd);
    failure = fmt::format("glImportMemoryFdEXT: GL error 0x{:x}", error);
    return false;
  }
  buffer = gl::Buffer();
  glNamedBufferStorageMemEXT(buffer.id(), static_cast<GLsizeiptr>(shared.size), memory.id(), 0);
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
    failure = fmt::format("glNamedBufferStorageMemEXT: GL error 0x{:x}", error);
    return false;
  }
  return true;
}

// A failed import is an expected answer (Mesa), logged once as a decision, not as a GL error.
class QuietGlDebugOutput {
 public:
  QuietGlDebugOutput() : wasOn_(glIsEnabled(GL_DEBUG_OUTPUT) == GL_TRUE) {
    if (wasOn_) glDisable(GL_DEBUG_OUTPUT);
  }
  ~QuietGlDebugOutput() {
    if (wasOn_) glEnable(GL_DEBUG_OUTPUT);
  }
  QuietGlDebugOutput(const QuietGlDebugOutput&) = delete;
  QuietGlDebugOutput& operator=(const QuietGlDebugOutput&) = delete;

 private:
  bool wasOn_;
};

bool glHasMemoryInterop() {
  const gl::Api& api = gl::api("GL_EXT_memory_object_fd");
  return api.EXT_memory_object != 0 && api.EXT_memory_object_fd != 0;
}

bool glHasSemaphoreInterop() {
  const gl::Api& api = gl::api("GL_EXT_semaphore_fd");
  return api.EXT_semaphore != 0 && api.EXT_semaphore_fd != 0;
}

}  // namespace

HitBatchTransport::HitBatchTransport(vk::ShadowTracer& tracer) : tracer_(tracer) {}
HitBatchTransport::~HitBatchTransport() = default;

std::string HitBatchTransport::name() const {
  switch (mode_) {
    case Mode::InteropSemaphores:
      return "interop";
    case Mode::InteropFinish:
      return "interop-finish";
    case Mode::Staging:
      return "staging";
    case Mode::Undecided:
      break;
  }
  return "undecided";
}

void HitBatchTransport::decide(std::uint32_t rays) {
  if (mode_ != Mode::Undecided) return;
  std::string why;
  if (!tracer_.info().externalMemoryFd) {
    why = "the Vulkan device cannot export memory";
  } else if (!glHasMemoryInterop()) {
    why = "the GL context has no GL_EXT_memory_object_fd";
  } else if (importAll(tracer_.hitBuffers(rays, vk::Transport::Interop))) {
    generation_ = tracer_.hitBuffers(rays, vk::Transport::Interop).generation;
    haveBuffers_ = true;
    mode_ = importSemaphores() ? Mode::InteropSemaphores : Mode::InteropFinish;
    spdlog::info("gi: closest-hit batches handed over in shared GPU memory ({})", name());
    return;
  } else {
    why = "GL could not use the Vulkan memory";
  }
  mode_ = Mode::Staging;
  spdlog::info("gi: closest-hit batches handed over through staging copies: {}", why);
}

bool HitBatchTransport::importAll(const vk::HitBuffers& buffers) {
  const QuietGlDebugOutput quiet;
  std::string failure;
  if (!importBuffer(buffers.rays, rays_.memory, rays_.buffer, failure)) {
    close(buffers.hits.fd);  // not tried: still ours
  } else if (importBuffer(buffers.hits, hits_.memory, hits_.buffer, failure)) {
    return true;
  }
  spdlog::info("gi: importing the closest-hit buffers into GL failed: {}", failure);
  return false;
}

bool HitBatchTransport::importSemaphores() {
  if (!tracer_.info().externalSemaphoreFd || !glHasSemaphoreInterop()) return false;
  const vk::SemaphoreFds fds = tracer_.exportHitSemaphores();
  // GL owns an fd once its import succeeds; a failed one is still ours to close.
  const auto import = [](gl::Semaphore& semaphore, int fd) {
    clearGlErrors();
    semaphore = gl::Semaphore();
    glImportSemaphoreFdEXT(semaphore.id(), GL_HANDLE_TYPE_OPAQUE_FD_EXT, fd);
    const GLenum error = glGetError();
    if (error == GL_NO_ERROR) return true;
    close(fd);
    spdlog::info("gi: importing a semaphore into GL failed (GL error 0x{:x})", error);
    return false;
  };
  if (!import(glDone_, fds.glDone)) {
    close(fds.vkDone);
    return false;
  }
  return import(vkDone_, fds.vkDone);
}

HitBatchTransport::GlBuffers HitBatchTransport::prepare(std::uint32_t rays) {
  decide(rays);
  if (mode_ == Mode::Staging) {
    const vk::HitBuffers& buffers = tracer_.hitBuffers(rays, vk::Transport::Staging);
    stagingRays_.reserve(static_cast<GLsizeiptr>(buffers.rays.size));
    stagingHits_.reserve(static_cast<GLsizeiptr>(buffers.hits.size));
    return {stagingRays_.id(), stagingHits_.id()};
  }
  const vk::HitBuffers& buffers = tracer_.hitBuffers(rays, vk::Transport::Interop);
  if (!haveBuffers_ || buffers.generation != generation_) {
    if (!importAll(buffers)) {
      throw Error(ErrorCode::Internal, "gi: GL could not import the grown closest-hit buffers");
    }
    generation_ = buffers.generation;
    haveBuffers_ = true;
  }
  return {rays_.buffer.id(), hits_.buffer.id()};
}

double HitBatchTransport::trace(const vk::TraceScene& scene, vk::TracePath path,
                                const vk::HitBatchShape& shape) {
  const Stopwatch cpu;
  if (mode_ == Mode::InteropSemaphores) {
    const std::array<GLuint, 2> buffers{rays_.buffer.id(), hits_.buffer.id()};
    glSignalSemaphoreEXT(glDone_.id(), static_cast<GLuint>(buffers.size()), buffers.data(), 0,
                         nullptr, nullptr);
    glFlush();
    tracer_.traceHits(scene, path, shape, true);
    glWaitSemaphoreEXT(vkDone_.id(), static_cast<GLuint>(buffers.size()), buffers.data(), 0,
                       nullptr, nullptr);
    return 0.0;
  }
  if (mode_ == Mode::InteropFinish) {
    glFinish();
    tracer_.traceHits(scene, path, shape, false);
    return cpu.elapsedMs();
  }
  const vk::HitBuffers& buffers = tracer_.hitBuffers(shape.rays, vk::Transport::Staging);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(stagingRays_.id(), 0,
                          static_cast<GLsizeiptr>(shape.rays * vk::kHitRayBytes),
                          buffers.rays.mapped);
  tracer_.traceHits(scene, path, shape, false);
  glNamedBufferSubData(stagingHits_.id(), 0,
                       static_cast<GLsizeiptr>(shape.rays * vk::kHitRecordBytes),
                       buffers.hits.mapped);
  return cpu.elapsedMs();
}

}  // namespace lgh
