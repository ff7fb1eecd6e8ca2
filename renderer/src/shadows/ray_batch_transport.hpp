// The GL side of the shadow-ray buffers, which the Vulkan tracer owns (vk/shadow_tracer.hpp):
// origins and targets that GL writes, visibility that GL reads, handed over by interop or staging
// copies (shadows/batch_transport.hpp).
#pragma once

#include <string>

#include "gl/gl_objects.hpp"
#include "shadows/batch_transport.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh {

class RayBatchTransport {
 public:
  // The tracer's buffers and semaphores of `lane` (vk::kRayLanes of them).
  RayBatchTransport(vk::ShadowTracer& tracer, vk::RayLane lane);

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
  // trace() in two halves (BatchTransport::handOver and awaitResults): GL commands issued in
  // between run while Vulkan traces.
  double handOver(const vk::TraceScene& scene, vk::TracePath path, const vk::RayBatchShape& shape,
                  const vk::TraceParams& params);
  void awaitResults() { transport_.awaitResults(); }
  bool resultsReady() const { return transport_.resultsReady(); }

  // "interop" (semaphores), "interop-finish" or "staging".
  std::string name() const { return transport_.name(); }

 private:
  BatchTransport::BuffersFor buffersFor(const vk::RayBatchShape& shape);

  vk::ShadowTracer& tracer_;
  vk::RayLane lane_;
  BatchTransport transport_;
};

}  // namespace lgh
