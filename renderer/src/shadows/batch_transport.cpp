#include "shadows/batch_transport.hpp"

#include <unistd.h>

#include <cstdlib>
#include <string_view>
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

// LGH_NO_PINNED_MEMORY set (and not "0"): staging copies instead of pinned memory.
bool pinningSwitchedOff() {
  const char* value = std::getenv("LGH_NO_PINNED_MEMORY");
  return value != nullptr && *value != '\0' && std::string_view(value) != "0";
}

// A GL buffer on `shared`'s mapped memory (GL_AMD_pinned_memory): GL reads and writes that memory
// itself, and does not keep it alive.
bool pinBuffer(const vk::SharedBuffer& shared, gl::Buffer& buffer, std::string& failure) {
  clearGlErrors();
  buffer = gl::Buffer();
  glBindBuffer(GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD, buffer.id());
  glBufferData(GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD, static_cast<GLsizeiptr>(shared.size),
               shared.mapped, GL_STREAM_COPY);
  glBindBuffer(GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD, 0);
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
    buffer = gl::Buffer::empty();
    failure =
        fmt::format("glBufferData(GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD): GL error 0x{:x}", error);
    return false;
  }
  return true;
}

}  // namespace

BatchTransport::BatchTransport(vk::ShadowTracer& tracer, BatchLayout layout)
    : tracer_(tracer),
      layout_(std::move(layout)),
      imported_(layout_.buffers.size()),
      staging_(layout_.buffers.size()) {
  pinned_.reserve(layout_.buffers.size());
  for (std::size_t i = 0; i < layout_.buffers.size(); ++i) pinned_.push_back(gl::Buffer::empty());
  if (layout_.buffers.empty() || layout_.buffers.size() > kMaxBatchBuffers ||
      !layout_.exportSemaphores) {
    throw Error(ErrorCode::Internal, fmt::format("{}: a batch transport of {} buffers",
                                                 layout_.logPrefix, layout_.buffers.size()));
  }
}
BatchTransport::~BatchTransport() = default;

std::string BatchTransport::name() const {
  switch (mode_) {
    case Mode::InteropSemaphores:
      return "interop";
    case Mode::InteropFinish:
      return "interop-finish";
    case Mode::Pinned:
      return "pinned";
    case Mode::Staging:
      return "staging";
    case Mode::Undecided:
      break;
  }
  return "undecided";
}

void BatchTransport::decide(const BuffersFor& buffersFor) {
  if (mode_ != Mode::Undecided) return;
  std::string why;
  if (!tracer_.info().externalMemoryFd) {
    why = "the Vulkan device cannot export memory";
  } else if (!glHasMemoryInterop()) {
    why = "the GL context has no GL_EXT_memory_object_fd";
  } else if (attach(buffersFor(vk::Transport::Interop), &BatchTransport::importAll)) {
    mode_ = importSemaphores() ? Mode::InteropSemaphores : Mode::InteropFinish;
    spdlog::info("{}: {} handed over in shared GPU memory ({})", layout_.logPrefix, layout_.batches,
                 name());
    return;
  } else {
    why = "GL could not use the Vulkan memory";
  }
  const std::string notPinned = tryPinning(buffersFor(vk::Transport::Staging));
  if (notPinned.empty()) {
    mode_ = Mode::Pinned;
    spdlog::info(
        "{}: {} handed over in Vulkan's mapped memory, pinned into GL "
        "(GL_AMD_pinned_memory): {}",
        layout_.logPrefix, layout_.batches, why);
    return;
  }
  mode_ = Mode::Staging;
  spdlog::info("{}: {} handed over through staging copies: {}; {}", layout_.logPrefix,
               layout_.batches, why, notPinned);
}

std::string BatchTransport::tryPinning(const BatchBuffers& buffers) {
  if (pinningSwitchedOff()) return "pinned memory switched off (LGH_NO_PINNED_MEMORY)";
  if (gl::api("GL_AMD_pinned_memory").AMD_pinned_memory == 0) {
    return "the GL context has no GL_AMD_pinned_memory";
  }
  if (!attach(buffers, &BatchTransport::pinAll)) return "GL could not pin the Vulkan memory";
  return {};
}

bool BatchTransport::attach(const BatchBuffers& buffers,
                            bool (BatchTransport::*attachAll)(const BatchBuffers&)) {
  if (haveBuffers_ && buffers.generation == generation_) return true;
  if (!(this->*attachAll)(buffers)) return false;
  generation_ = buffers.generation;
  haveBuffers_ = true;
  return true;
}

bool BatchTransport::pinAll(const BatchBuffers& buffers) {
  const QuietGlDebugOutput quiet;
  std::string failure;
  for (std::size_t i = 0; i < pinned_.size(); ++i) {
    if (buffers.parts[i]->mapped == nullptr) {
      failure = "the Vulkan memory is not mapped";
    } else if (pinBuffer(*buffers.parts[i], pinned_[i], failure)) {
      continue;
    }
    spdlog::info("{}: pinning the {} into GL failed: {}", layout_.logPrefix, layout_.bufferNames,
                 failure);
    for (gl::Buffer& buffer : pinned_) buffer = gl::Buffer::empty();
    return false;
  }
  return true;
}

bool BatchTransport::importAll(const BatchBuffers& buffers) {
  const QuietGlDebugOutput quiet;
  std::string failure;
  const std::size_t count = imported_.size();
  for (std::size_t i = 0; i < count; ++i) {
    Imported& imported = imported_[i];
    if (importBuffer(*buffers.parts[i], imported.memory, imported.buffer, failure)) continue;
    // The fds of the buffers not tried yet are still ours.
    for (std::size_t rest = i + 1; rest < count; ++rest) close(buffers.parts[rest]->fd);
    spdlog::info("{}: importing the {} into GL failed: {}", layout_.logPrefix, layout_.bufferNames,
                 failure);
    return false;
  }
  return true;
}

bool BatchTransport::importSemaphores() {
  if (!tracer_.info().externalSemaphoreFd || !glHasSemaphoreInterop()) return false;
  const vk::SemaphoreFds fds = layout_.exportSemaphores(tracer_);
  // GL owns an fd once its import succeeds; a failed one is still ours to close.
  const auto import = [this](gl::Semaphore& semaphore, int fd) {
    clearGlErrors();
    semaphore = gl::Semaphore();
    glImportSemaphoreFdEXT(semaphore.id(), GL_HANDLE_TYPE_OPAQUE_FD_EXT, fd);
    const GLenum error = glGetError();
    if (error == GL_NO_ERROR) return true;
    close(fd);
    spdlog::info("{}: importing a semaphore into GL failed (GL error 0x{:x})", layout_.logPrefix,
                 error);
    return false;
  };
  if (!import(glDone_, fds.glDone)) {
    close(fds.vkDone);
    return false;
  }
  return import(vkDone_, fds.vkDone);
}

std::span<const GLuint> BatchTransport::prepare(const BuffersFor& buffersFor) {
  decide(buffersFor);
  const std::size_t count = layout_.buffers.size();
  if (mode_ == Mode::Pinned) {
    // GL does not keep pinned memory alive: nothing of GL's may still use it when Vulkan grows
    // the buffers below (on a CPU rasterizer the batch's passes wait for the same work anyway).
    glFinish();
    if (!attach(buffersFor(vk::Transport::Staging), &BatchTransport::pinAll)) {
      throw Error(ErrorCode::Internal, fmt::format("{}: GL could not pin the grown {}",
                                                   layout_.logPrefix, layout_.bufferNames));
    }
    for (std::size_t i = 0; i < count; ++i) ids_[i] = pinned_[i].id();
    return {ids_.data(), count};
  }
  if (mode_ == Mode::Staging) {
    const BatchBuffers buffers = buffersFor(vk::Transport::Staging);
    for (std::size_t i = 0; i < count; ++i) {
      staging_[i].reserve(static_cast<GLsizeiptr>(buffers.parts[i]->size));
      ids_[i] = staging_[i].id();
    }
    return {ids_.data(), count};
  }
  if (!attach(buffersFor(vk::Transport::Interop), &BatchTransport::importAll)) {
    throw Error(ErrorCode::Internal, fmt::format("{}: GL could not import the grown {}",
                                                 layout_.logPrefix, layout_.bufferNames));
  }
  for (std::size_t i = 0; i < count; ++i) ids_[i] = imported_[i].buffer.id();
  return {ids_.data(), count};
}

std::pair<std::array<GLuint, kMaxBatchBuffers>, GLuint> BatchTransport::interopBuffers(
    bool BatchBufferUse::*named) const {
  std::array<GLuint, kMaxBatchBuffers> ids{};
  GLuint count = 0;
  for (std::size_t i = 0; i < layout_.buffers.size(); ++i) {
    if (layout_.buffers[i].*named) ids[count++] = imported_[i].buffer.id();
  }
  return {ids, count};
}

double BatchTransport::trace(const BuffersFor& buffersFor, std::span<const std::uint64_t> bytes,
                             const TraceOnVulkan& traceOnVulkan) {
  const Stopwatch cpu;
  handOver(buffersFor, bytes, traceOnVulkan);
  awaitResults();
  return cpu.elapsedMs();
}

bool BatchTransport::resultsReady() const {
  return submittedTrace_ == 0 || tracer_.traceFinished(submittedTrace_);
}

void BatchTransport::awaitResults() {
  if (submittedTrace_ != 0) {
    const std::uint64_t trace = std::exchange(submittedTrace_, 0);
    tracer_.awaitTrace(trace);
    for (std::size_t i = 0; i < layout_.buffers.size(); ++i) {
      const auto [mapped, bytes] = std::exchange(copyBack_[i], {});
      if (mapped == nullptr) continue;
      glNamedBufferSubData(staging_[i].id(), 0, static_cast<GLsizeiptr>(bytes), mapped);
    }
    return;
  }
  if (mode_ != Mode::InteropSemaphores) return;
  const auto [waited, waitCount] = interopBuffers(&BatchBufferUse::waited);
  glWaitSemaphoreEXT(vkDone_.id(), waitCount, waited.data(), 0, nullptr, nullptr);
}

double BatchTransport::handOver(const BuffersFor& buffersFor, std::span<const std::uint64_t> bytes,
                                const TraceOnVulkan& traceOnVulkan,
                                const SubmitOnVulkan& submitOnVulkan) {
  if (bytes.size() != layout_.buffers.size()) {
    throw Error(ErrorCode::Internal, fmt::format("{}: a batch traced with the sizes of {} buffers",
                                                 layout_.logPrefix, bytes.size()));
  }
  if (submittedTrace_ != 0) awaitResults();  // a caller that skipped it: its copies come first
  const Stopwatch cpu;
  if (mode_ == Mode::InteropSemaphores) {
    const auto [signalled, signalCount] = interopBuffers(&BatchBufferUse::signalled);
    glSignalSemaphoreEXT(glDone_.id(), signalCount, signalled.data(), 0, nullptr, nullptr);
    glFlush();
    traceOnVulkan(true);
    return cpu.elapsedMs();
  }
  if (mode_ == Mode::InteropFinish) {
    glFinish();
    traceOnVulkan(false);
    return cpu.elapsedMs();
  }
  if (mode_ == Mode::Pinned) {
    // GL's writes are in the memory Vulkan reads once GL has finished; Vulkan's results are where
    // GL reads them once the trace's fence has signalled (awaitResults, or traceOnVulkan).
    glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
    glFinish();
    if (submitOnVulkan) {
      submittedTrace_ = submitOnVulkan();
    } else {
      traceOnVulkan(false);
    }
    return cpu.elapsedMs();
  }
  const BatchBuffers buffers = buffersFor(vk::Transport::Staging);
  const std::size_t count = layout_.buffers.size();
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  for (std::size_t i = 0; i < count; ++i) {
    if (!layout_.buffers[i].glWrites) continue;
    glGetNamedBufferSubData(staging_[i].id(), 0, static_cast<GLsizeiptr>(bytes[i]),
                            buffers.parts[i]->mapped);
  }
  if (submitOnVulkan) {
    // The copies back wait for awaitResults(): GL draws on while Vulkan traces.
    submittedTrace_ = submitOnVulkan();
    for (std::size_t i = 0; i < count; ++i) {
      if (!layout_.buffers[i].glWrites) copyBack_[i] = {buffers.parts[i]->mapped, bytes[i]};
    }
    return cpu.elapsedMs();
  }
  traceOnVulkan(false);
  for (std::size_t i = 0; i < count; ++i) {
    if (layout_.buffers[i].glWrites) continue;
    glNamedBufferSubData(staging_[i].id(), 0, static_cast<GLsizeiptr>(bytes[i]),
                         buffers.parts[i]->mapped);
  }
  return cpu.elapsedMs();
}

}  // namespace lgh
