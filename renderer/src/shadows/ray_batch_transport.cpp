#include "shadows/ray_batch_transport.hpp"

#include <array>

namespace lgh {
namespace {

// GL writes the origins and targets and signals when they are written; Vulkan writes the
// visibility, which GL waits for.
BatchLayout rayBatchLayout(vk::RayLane lane) {
  return {.logPrefix = "shadows",
          .batches = "rays",
          .bufferNames = "ray buffers",
          .buffers = {{.glWrites = true, .signalled = true},
                      {.glWrites = true, .signalled = true},
                      {.waited = true}},
          .exportSemaphores = [lane](vk::ShadowTracer& tracer) {
            return tracer.exportSemaphores(lane);
          }};
}

}  // namespace

RayBatchTransport::RayBatchTransport(vk::ShadowTracer& tracer, vk::RayLane lane)
    : tracer_(tracer), lane_(lane), transport_(tracer, rayBatchLayout(lane)) {}

// For the call at hand: `shape` outlives it.
BatchTransport::BuffersFor RayBatchTransport::buffersFor(const vk::RayBatchShape& shape) {
  return [this, &shape](vk::Transport transport) {
    const vk::RayBuffers& buffers = tracer_.rayBuffers(shape, transport, lane_);
    return BatchBuffers{.generation = buffers.generation,
                        .parts = {&buffers.origins, &buffers.targets, &buffers.visibility}};
  };
}

RayBatchTransport::GlBuffers RayBatchTransport::prepare(const vk::RayBatchShape& shape) {
  const std::span<const GLuint> ids = transport_.prepare(buffersFor(shape));
  return {ids[0], ids[1], ids[2]};
}

namespace {

std::array<std::uint64_t, 3> batchBytes(const vk::RayBatchShape& shape) {
  return {shape.pixels() * 16, shape.pixels() * shape.raysPerPixel * 16,
          shape.pixels() * shape.words() * 4};
}

}  // namespace

double RayBatchTransport::trace(const vk::TraceScene& scene, vk::TracePath path,
                                const vk::RayBatchShape& shape, const vk::TraceParams& params) {
  const double ms = handOver(scene, path, shape, params);
  awaitResults();
  return ms;
}

double RayBatchTransport::handOver(const vk::TraceScene& scene, vk::TracePath path,
                                   const vk::RayBatchShape& shape, const vk::TraceParams& params) {
  return transport_.handOver(
      buffersFor(shape), batchBytes(shape),
      [&](bool useSemaphores) { tracer_.trace(scene, path, shape, params, useSemaphores, lane_); },
      [&] { return tracer_.submitTrace(scene, path, shape, params, lane_); });
}

}  // namespace lgh
