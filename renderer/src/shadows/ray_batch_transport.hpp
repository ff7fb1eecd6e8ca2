// The GL side of the shadow-ray buffers, which the Vulkan tracer owns (vk/shadow_tracer.hpp):
//   interop   the Vulkan memory imported into GL buffers (GL_EXT_memory_object_fd): the rays and
//             their visibility never leave the GPU. Synchronized with imported semaphores
//             (GL_EXT_semaphore_fd) where both sides have them, else with glFinish and a fence.
//   staging   GL buffers of its own, copied into and out of Vulkan's mapped host memory, where the
//             drivers cannot share memory (Mesa: llvmpipe cannot back a buffer with lavapipe
//             memory) - so CI still runs every step of the shadowed frame.
// The transport is chosen once, on the first batch, by trying interop; the choice is logged.
#pragma once

#include <cstdint>
#include <string>

#include "gl/gl_objects.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh {

class RayBatchTransport {
 public:
  explicit RayBatchTransport(vk::ShadowTracer& tracer);
  ~RayBatchTransport();
  RayBatchTransport(const RayBatchTransport&) = delete;
  RayBatchTransport& operator=(const RayBatchTransport&) = delete;

  struct GlBuffers {
    GLuint origins = 0;
    GLuint targets = 0;
    GLuint visibility = 0;
  };
  // GL buffers that hold a batch of this shape (reallocated as needed).
  GlBuffers prepare(const vk::RayBatchShape& shape);

  // Hands the origins and targets that GL wrote to Vulkan, traces them, and makes the visibility
  // visible to GL's next commands. Returns the CPU milliseconds spent copying (staging) and
  // waiting (finish/fence); 0 with semaphores.
  double trace(const vk::TraceScene& scene, vk::TracePath path, const vk::RayBatchShape& shape,
               const vk::TraceParams& params);

  // "interop" (semaphores), "interop-finish" or "staging".
  std::string name() const;

 private:
  enum class Mode { Undecided, InteropSemaphores, InteropFinish, Staging };
  struct Imported {
    gl::MemoryObject memory = gl::MemoryObject::empty();
    gl::Buffer buffer = gl::Buffer::empty();
  };

  void decide(const vk::RayBatchShape& shape);
  bool importAll(const vk::RayBuffers& buffers);
  bool importSemaphores();
  void allocateStaging(const vk::RayBuffers& buffers);

  vk::ShadowTracer& tracer_;
  Mode mode_ = Mode::Undecided;
  std::uint64_t generation_ = 0;
  bool haveBuffers_ = false;
  Imported origins_;
  Imported targets_;
  Imported visibility_;
  gl::SizedBuffer stagingOrigins_;
  gl::SizedBuffer stagingTargets_;
  gl::SizedBuffer stagingVisibility_;
  gl::Semaphore glDone_ = gl::Semaphore::empty();
  gl::Semaphore vkDone_ = gl::Semaphore::empty();
};

}  // namespace lgh
