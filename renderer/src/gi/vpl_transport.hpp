// The GL side of the light paths' VPL buffer, which the Vulkan tracer owns and fills in one
// submission (vk/shadow_tracer.hpp, "Light paths"): handed over by interop (with the tracer's
// light-path semaphores: GL signals once it is done reading the last VPLs, Vulkan once it has
// written the new ones) or by a staging copy, as the shadow rays are
// (shadows/batch_transport.hpp).
#pragma once

#include <cstdint>
#include <string>

#include "gl/gl_objects.hpp"
#include "shadows/batch_transport.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh {

class VplTransport {
 public:
  explicit VplTransport(vk::ShadowTracer& tracer);

  // The GL buffer that holds `vplCount` VPLs once trace() returns (reallocated as needed).
  GLuint prepare(std::uint32_t vplCount);

  // Traces the light paths on Vulkan into the buffer and makes the VPLs visible to GL's next
  // commands. Returns the CPU milliseconds spent copying (staging) and waiting (finish); 0 with
  // semaphores.
  double trace(const vk::TraceScene& scene, vk::TracePath path, const vk::LightPathScene& surfaces,
               const vk::LightPathBatch& batch);

  // "interop" (semaphores), "interop-finish" or "staging".
  std::string name() const { return transport_.name(); }

 private:
  BatchTransport::BuffersFor buffersFor(std::uint32_t vplCount);

  vk::ShadowTracer& tracer_;
  BatchTransport transport_;
};

}  // namespace lgh
