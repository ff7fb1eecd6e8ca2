#include "gi/hit_batch_transport.hpp"

#include <array>

namespace lgh {
namespace {

// GL writes the rays; Vulkan writes the hits. Both buffers are named in the semaphore signal and
// wait.
BatchLayout hitBatchLayout() {
  return {
      .logPrefix = "gi",
      .batches = "closest-hit batches",
      .bufferNames = "closest-hit buffers",
      .buffers = {{.glWrites = true, .signalled = true, .waited = true},
                  {.glWrites = false, .signalled = true, .waited = true}},
      .exportSemaphores = [](vk::ShadowTracer& tracer) { return tracer.exportHitSemaphores(); }};
}

}  // namespace

HitBatchTransport::HitBatchTransport(vk::ShadowTracer& tracer)
    : tracer_(tracer), transport_(tracer, hitBatchLayout()) {}

BatchTransport::BuffersFor HitBatchTransport::buffersFor(std::uint32_t rays) {
  return [this, rays](vk::Transport transport) {
    const vk::HitBuffers& buffers = tracer_.hitBuffers(rays, transport);
    return BatchBuffers{.generation = buffers.generation, .parts = {&buffers.rays, &buffers.hits}};
  };
}

HitBatchTransport::GlBuffers HitBatchTransport::prepare(std::uint32_t rays) {
  const std::span<const GLuint> ids = transport_.prepare(buffersFor(rays));
  return {ids[0], ids[1]};
}

double HitBatchTransport::trace(const vk::TraceScene& scene, vk::TracePath path,
                                const vk::HitBatchShape& shape) {
  const std::array<std::uint64_t, 2> bytes{shape.rays * vk::kHitRayBytes,
                                           shape.rays * vk::kHitRecordBytes};
  return transport_.trace(buffersFor(shape.rays), bytes, [&](bool useSemaphores) {
    tracer_.traceHits(scene, path, shape, useSemaphores);
  });
}

}  // namespace lgh
