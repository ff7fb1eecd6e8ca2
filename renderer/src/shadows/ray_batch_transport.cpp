#include "shadows/ray_batch_transport.hpp"

#include <unistd.h>

#include <array>
#include <utility>

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

// Silences the GL debug output while interop is tried: a failed import is an expected answer
// (Mesa) and is logged once as a decision, not as a GL error.
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

RayBatchTransport::RayBatchTransport(vk::ShadowTracer& tracer) : tracer_(tracer) {}
RayBatchTransport::~RayBatchTransport() = default;

std::string RayBatchTransport::name() const {
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

void RayBatchTransport::decide(const vk::RayBatchShape& shape) {
  if (mode_ != Mode::Undecided) return;
  std::string why;
  if (!tracer_.info().externalMemoryFd) {
    why = "the Vulkan device cannot export memory";
  } else if (!glHasMemoryInterop()) {
    why = "the GL context has no GL_EXT_memory_object_fd";
  } else if (importAll(tracer_.rayBuffers(shape, vk::Transport::Interop))) {
    generation_ = tracer_.rayBuffers(shape, vk::Transport::Interop).generation;
    haveBuffers_ = true;
    mode_ = importSemaphores() ? Mode::InteropSemaphores : Mode::InteropFinish;
    spdlog::info("shadows: rays handed over in shared GPU memory ({})", name());
    return;
  } else {
    why = "GL could not use the Vulkan memory";
  }
  mode_ = Mode::Staging;
  spdlog::info("shadows: rays handed over through staging copies: {}", why);
}

bool RayBatchTransport::importAll(const vk::RayBuffers& buffers) {
  const QuietGlDebugOutput quiet;
  const std::array<std::pair<const vk::SharedBuffer*, Imported*>, 3> parts{{
      {&buffers.origins, &origins_},
      {&buffers.targets, &targets_},
      {&buffers.visibility, &visibility_},
  }};
  std::string failure;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    auto [shared, imported] = parts[i];
    if (importBuffer(*shared, imported->memory, imported->buffer, failure)) continue;
    // The fds of the buffers not tried yet are still ours.
    for (std::size_t rest = i + 1; rest < parts.size(); ++rest) close(parts[rest].first->fd);
    spdlog::info("shadows: importing the ray buffers into GL failed: {}", failure);
    return false;
  }
  return true;
}

bool RayBatchTransport::importSemaphores() {
  if (!tracer_.info().externalSemaphoreFd || !glHasSemaphoreInterop()) return false;
  const vk::SemaphoreFds fds = tracer_.exportSemaphores();
  // GL owns an fd once its import succeeds; a failed one is still ours to close.
  const auto import = [](gl::Semaphore& semaphore, int fd) {
    clearGlErrors();
    semaphore = gl::Semaphore();
    glImportSemaphoreFdEXT(semaphore.id(), GL_HANDLE_TYPE_OPAQUE_FD_EXT, fd);
    const GLenum error = glGetError();
    if (error == GL_NO_ERROR) return true;
    close(fd);
    spdlog::info("shadows: importing a semaphore into GL failed (GL error 0x{:x})", error);
    return false;
  };
  if (!import(glDone_, fds.glDone)) {
    close(fds.vkDone);
    return false;
  }
  return import(vkDone_, fds.vkDone);
}

void RayBatchTransport::allocateStaging(const vk::RayBuffers& buffers) {
  stagingOrigins_.reserve(static_cast<GLsizeiptr>(buffers.origins.size));
  stagingTargets_.reserve(static_cast<GLsizeiptr>(buffers.targets.size));
  stagingVisibility_.reserve(static_cast<GLsizeiptr>(buffers.visibility.size));
}

RayBatchTransport::GlBuffers RayBatchTransport::prepare(const vk::RayBatchShape& shape) {
  decide(shape);
  if (mode_ == Mode::Staging) {
    allocateStaging(tracer_.rayBuffers(shape, vk::Transport::Staging));
    return {stagingOrigins_.id(), stagingTargets_.id(), stagingVisibility_.id()};
  }
  const vk::RayBuffers& buffers = tracer_.rayBuffers(shape, vk::Transport::Interop);
  if (!haveBuffers_ || buffers.generation != generation_) {
    if (!importAll(buffers)) {
      throw Error(ErrorCode::Internal, "shadows: GL could not import the grown ray buffers");
    }
    generation_ = buffers.generation;
    haveBuffers_ = true;
  }
  return {origins_.buffer.id(), targets_.buffer.id(), visibility_.buffer.id()};
}

double RayBatchTransport::trace(const vk::TraceScene& scene, vk::TracePath path,
                                const vk::RayBatchShape& shape, const vk::TraceParams& params) {
  const Stopwatch cpu;
  if (mode_ == Mode::InteropSemaphores) {
    const std::array<GLuint, 2> inputs{origins_.buffer.id(), targets_.buffer.id()};
    glSignalSemaphoreEXT(glDone_.id(), static_cast<GLuint>(inputs.size()), inputs.data(), 0,
                         nullptr, nullptr);
    glFlush();
    tracer_.trace(scene, path, shape, params, true);
    const GLuint output = visibility_.buffer.id();
    glWaitSemaphoreEXT(vkDone_.id(), 1, &output, 0, nullptr, nullptr);
    return 0.0;
  }
  if (mode_ == Mode::InteropFinish) {
    glFinish();
    tracer_.trace(scene, path, shape, params, false);
    return cpu.elapsedMs();
  }
  const vk::RayBuffers& buffers = tracer_.rayBuffers(shape, vk::Transport::Staging);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(stagingOrigins_.id(), 0, static_cast<GLsizeiptr>(shape.pixels() * 16),
                          buffers.origins.mapped);
  glGetNamedBufferSubData(stagingTargets_.id(), 0,
                          static_cast<GLsizeiptr>(shape.pixels() * shape.raysPerPixel * 16),
                          buffers.targets.mapped);
  tracer_.trace(scene, path, shape, params, false);
  glNamedBufferSubData(stagingVisibility_.id(), 0,
                       static_cast<GLsizeiptr>(shape.pixels() * shape.words() * 4),
                       buffers.visibility.mapped);
  return cpu.elapsedMs();
}

}  // namespace lgh
