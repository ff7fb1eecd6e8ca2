// The GL side of the closest-hit batch buffers, which the Vulkan tracer owns
// (vk/shadow_tracer.hpp, "Closest hits"), as shadows/ray_batch_transport.hpp is for shadow rays:
//   interop   the Vulkan memory imported into GL buffers: rays and hits never leave the GPU;
//             synchronized with the tracer's hit semaphores where both sides have them, else
//             with glFinish and a fence;
//   staging   GL buffers of its own, copied into and out of Vulkan's mapped host memory (Mesa:
//             llvmpipe cannot back a GL buffer with lavapipe memory).
// Chosen once, on the first batch, by trying interop; the choice is logged.
#pragma once

#include <cstdint>
#include <string>

#include "gl/gl_objects.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh {

class HitBatchTransport {
 public:
  explicit HitBatchTransport(vk::ShadowTracer& tracer);
  ~HitBatchTransport();
  HitBatchTransport(const HitBatchTransport&) = delete;
  HitBatchTransport& operator=(const HitBatchTransport&) = delete;

  struct GlBuffers {
    GLuint rays = 0;  // 2 x vec4 per ray (GL writes)
    GLuint hits = 0;  // HitRecord per ray (GL reads)
  };
  // GL buffers that hold a batch of `rays` rays (reallocated as needed).
  GlBuffers prepare(std::uint32_t rays);

  // Hands the rays GL wrote to Vulkan, traces them, and makes the hits visible to GL's next
  // commands. Returns the CPU milliseconds spent copying (staging) and waiting (finish); 0 with
  // semaphores.
  double trace(const vk::TraceScene& scene, vk::TracePath path, const vk::HitBatchShape& shape);

  // "interop" (semaphores), "interop-finish" or "staging".
  std::string name() const;

 private:
  enum class Mode { Undecided, InteropSemaphores, InteropFinish, Staging };
  struct Imported {
    gl::MemoryObject memory = gl::MemoryObject::empty();
    gl::Buffer buffer = gl::Buffer::empty();
  };

  void decide(std::uint32_t rays);
  bool importAll(const vk::HitBuffers& buffers);
  bool importSemaphores();

  vk::ShadowTracer& tracer_;
  Mode mode_ = Mode::Undecided;
  std::uint64_t generation_ = 0;
  bool haveBuffers_ = false;
  Imported rays_;
  Imported hits_;
  gl::SizedBuffer stagingRays_;
  gl::SizedBuffer stagingHits_;
  gl::Semaphore glDone_ = gl::Semaphore::empty();
  gl::Semaphore vkDone_ = gl::Semaphore::empty();
};

}  // namespace lgh
