#include "shadows/ray_batch_transport.hpp"

#include <array>

namespace lgh {
namespace {

// GL writes the origins and targets and signals when they are written; Vulkan writes the
// visibility, which GL waits for.
BatchLayout rayBatchLayout() {
  return {.logPrefix = "shadows",
          .batches = "rays",
          .bufferNames = "ray buffers",
          .buffers = {{.glWrites = true, .signalled = true},
                      {.glWrites = true, .signalled = true},
                      {.waited = true}},
          .exportSemaphores = &vk::ShadowTracer::exportSemaphores};
}

}  // namespace

RayBatchTransport::RayBatchTransport(vk::ShadowTracer& tracer)
    : tracer_(tracer), transport_(tracer, rayBatchLayout()) {}

// For the call at hand: `shape` outlives it.
BatchTransport::BuffersFor RayBatchTransport::buffersFor(const vk::RayBatchShape& shape) {
  return [this, &shape](vk::Transport transport) {
    const vk::RayBuffers& buffers = tracer_.rayBuffers(shape, transport);
    return BatchBuffers{.generation = buffers.generation,
                        .parts = {&buffers.origins, &buffers.targets, &buffers.visibility}};
  };
}

RayBatchTransport::GlBuffers RayBatchTransport::prepare(const vk::RayBatchShape& shape) {
  const std::span<const GLuint> ids = transport_.prepare(buffersFor(shape));
  return {ids[0], ids[1], ids[2]};
}

double RayBatchTransport::trace(const vk::TraceScene& scene, vk::TracePath path,
                                const vk::RayBatchShape& shape, const vk::TraceParams& params) {
  const std::array<std::uint64_t, 3> bytes{shape.pixels() * 16,
                                           shape.pixels() * shape.raysPerPixel * 16,
                                           shape.pixels() * shape.words() * 4};
  return transport_.trace(buffersFor(shape), bytes, [&](bool useSemaphores) {
    tracer_.trace(scene, path, shape, params, useSemaphores);
  });
}

}  // namespace lgh
