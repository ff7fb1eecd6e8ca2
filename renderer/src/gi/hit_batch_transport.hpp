// The GL side of the closest-hit batch buffers, which the Vulkan tracer owns
// (vk/shadow_tracer.hpp, "Closest hits"): rays that GL writes and hits that GL reads, handed over
// by interop (with the tracer's hit semaphores) or staging copies, as the shadow rays are
// (shadows/batch_transport.hpp).
#pragma once

#include <cstdint>
#include <string>

#include "gl/gl_objects.hpp"
#include "shadows/batch_transport.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh {

class HitBatchTransport {
 public:
  explicit HitBatchTransport(vk::ShadowTracer& tracer);

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
  std::string name() const { return transport_.name(); }

 private:
  BatchTransport::BuffersFor buffersFor(std::uint32_t rays);

  vk::ShadowTracer& tracer_;
  BatchTransport transport_;
};

}  // namespace lgh
