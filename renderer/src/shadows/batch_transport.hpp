// The GL side of a trace batch whose buffers the Vulkan tracer owns (vk/shadow_tracer.hpp):
//   interop   the Vulkan memory imported into GL buffers (GL_EXT_memory_object_fd): the batch
//             never leaves the GPU. Synchronized with imported semaphores (GL_EXT_semaphore_fd)
//             where both sides have them, else with glFinish and a fence.
//   pinned    where GL cannot import Vulkan's memory but can make a buffer on client memory
//             (GL_AMD_pinned_memory; Mesa's llvmpipe with lavapipe): GL buffers made on Vulkan's
//             mapped host memory, so GL writes the batch where Vulkan reads it and reads what
//             Vulkan wrote where it wrote it, with no copy. Synchronized with glFinish and a fence.
//   staging   GL buffers of its own, copied into and out of Vulkan's mapped host memory, where the
//             drivers share no memory at all, or with LGH_NO_PINNED_MEMORY set (which keeps this
//             mode tested where pinning works).
// The transport is chosen once, on the first batch, by trying interop, then pinning; the choice
// is logged.
// One kind of batch differs from another only in its buffers and its words in the log
// (BatchLayout): shadow rays (shadows/ray_batch_transport.hpp) and closest hits
// (gi/hit_batch_transport.hpp) are this transport with their layouts.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gl/gl_objects.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh {

// One buffer of a batch, as GL uses it around a trace.
struct BatchBufferUse {
  // GL writes it before the trace (staging: copied to Vulkan before), else GL reads it after the
  // trace (staging: copied back after).
  bool glWrites = false;
  bool signalled = false;  // named in the semaphore GL signals before the trace
  bool waited = false;     // named in the semaphore GL waits on after the trace
};

struct BatchLayout {
  std::string_view logPrefix;           // "shadows"
  std::string_view batches;             // what is handed over, for the log: "rays"
  std::string_view bufferNames;         // the buffers, for the log and errors: "ray buffers"
  std::vector<BatchBufferUse> buffers;  // in the order of BatchBuffers::parts
  // The tracer's semaphore export for this kind of batch (and lane).
  std::function<vk::SemaphoreFds(vk::ShadowTracer&)> exportSemaphores;
};

inline constexpr std::size_t kMaxBatchBuffers = 3;

// The tracer's buffers for one batch shape, in the layout's order.
struct BatchBuffers {
  std::uint64_t generation = 0;
  std::array<const vk::SharedBuffer*, kMaxBatchBuffers> parts{};
};

class BatchTransport {
 public:
  // The tracer's buffers of the batch at hand in a transport (its rayBuffers or hitBuffers).
  using BuffersFor = std::function<BatchBuffers(vk::Transport)>;
  // Traces the batch at hand on the tracer, with or without the semaphores.
  using TraceOnVulkan = std::function<void(bool useSemaphores)>;
  // Submits the batch at hand without semaphores and returns the trace's number, which
  // ShadowTracer::awaitTrace waits for (ShadowTracer::submitTrace).
  using SubmitOnVulkan = std::function<std::uint64_t()>;

  BatchTransport(vk::ShadowTracer& tracer, BatchLayout layout);
  ~BatchTransport();
  BatchTransport(const BatchTransport&) = delete;
  BatchTransport& operator=(const BatchTransport&) = delete;

  // GL buffers that hold the batch, in the layout's order (reallocated as needed).
  std::span<const GLuint> prepare(const BuffersFor& buffersFor);

  // Hands what GL wrote to Vulkan, traces it, and makes what Vulkan wrote visible to GL's next
  // commands: handOver() then awaitResults(). `bytes`: of each buffer the batch uses (the staging
  // copies). Returns the CPU milliseconds of the hand-over: copying (staging), waiting (finish),
  // or signalling the semaphores and recording and submitting Vulkan's commands (semaphores).
  double trace(const BuffersFor& buffersFor, std::span<const std::uint64_t> bytes,
               const TraceOnVulkan& traceOnVulkan);
  // The first half of trace(): with semaphores, GL signals and Vulkan's trace is submitted, and
  // GL's commands issued before awaitResults() run while Vulkan traces (they must not touch the
  // batch's buffers). Staging with `submitOnVulkan` copies GL's inputs over and submits the
  // trace, which runs while the CPU goes on; without it, and interop-finish, finish the whole
  // trace here.
  double handOver(const BuffersFor& buffersFor, std::span<const std::uint64_t> bytes,
                  const TraceOnVulkan& traceOnVulkan, const SubmitOnVulkan& submitOnVulkan = {});
  // The second half: GL's next commands wait for the trace handed over last (semaphores), or
  // the CPU waits for it and copies its results back (staging with a submitted trace); the
  // other transports have nothing left to do. Once per handOver().
  void awaitResults();
  // Whether awaitResults() would return without waiting for Vulkan: no trace is pending, or its
  // fence has signalled (with semaphores, GL itself waits on the GPU: always).
  bool resultsReady() const;

  // "interop" (semaphores), "interop-finish", "pinned" or "staging".
  std::string name() const;

 private:
  enum class Mode { Undecided, InteropSemaphores, InteropFinish, Pinned, Staging };
  struct Imported {
    gl::MemoryObject memory = gl::MemoryObject::empty();
    gl::Buffer buffer = gl::Buffer::empty();
  };

  void decide(const BuffersFor& buffersFor);
  // GL's buffers on `buffers` (importAll or pinAll as `attachAll`), unless they were made for
  // their generation already; false when GL refuses them.
  bool attach(const BatchBuffers& buffers, bool (BatchTransport::*attachAll)(const BatchBuffers&));
  bool importAll(const BatchBuffers& buffers);
  // Why the batch cannot go through pinned memory, or "" when pinAll(buffers) succeeded.
  std::string tryPinning(const BatchBuffers& buffers);
  // All or none: a failure releases the buffers pinned before it.
  bool pinAll(const BatchBuffers& buffers);
  bool importSemaphores();
  // The interop GL buffers whose use says `named` (signalled or waited), and how many.
  std::pair<std::array<GLuint, kMaxBatchBuffers>, GLuint> interopBuffers(
      bool BatchBufferUse::*named) const;

  vk::ShadowTracer& tracer_;
  BatchLayout layout_;
  Mode mode_ = Mode::Undecided;
  std::uint64_t generation_ = 0;
  bool haveBuffers_ = false;
  std::vector<Imported> imported_;
  std::vector<gl::Buffer> pinned_;  // on Vulkan's mapped memory, which GL does not keep alive
  std::vector<gl::SizedBuffer> staging_;
  std::array<GLuint, kMaxBatchBuffers> ids_{};
  gl::Semaphore glDone_ = gl::Semaphore::empty();
  gl::Semaphore vkDone_ = gl::Semaphore::empty();
  // Staging: the trace submitted last and not awaited yet (0: none), and what to copy back after
  // it: per buffer Vulkan's mapped bytes and their count (null: a buffer GL wrote).
  std::uint64_t submittedTrace_ = 0;
  std::array<std::pair<const void*, std::uint64_t>, kMaxBatchBuffers> copyBack_{};
};

}  // namespace lgh
