#include "gi/vpl_transport.hpp"

#include <array>

#include "lightgrid/lgh_types.hpp"

namespace lgh {
namespace {

static_assert(sizeof(PointLight) == vk::kVplBytes, "a VPL slot is one PointLight");

// Vulkan writes the VPLs; GL reads them. The buffer is named in the semaphore signal (GL's reads
// of the last VPLs are done) and the wait (the new ones are written).
BatchLayout vplLayout() {
  return {.logPrefix = "gi",
          .batches = "light-path VPLs",
          .bufferNames = "VPL buffer",
          .buffers = {{.glWrites = false, .signalled = true, .waited = true}},
          .exportSemaphores = [](vk::ShadowTracer& tracer) {
            return tracer.exportLightPathSemaphores();
          }};
}

}  // namespace

VplTransport::VplTransport(vk::ShadowTracer& tracer)
    : tracer_(tracer), transport_(tracer, vplLayout()) {}

BatchTransport::BuffersFor VplTransport::buffersFor(std::uint32_t vplCount) {
  return [this, vplCount](vk::Transport transport) {
    const vk::VplBuffers& buffers = tracer_.vplBuffers(vplCount, transport);
    return BatchBuffers{.generation = buffers.generation, .parts = {&buffers.vpls}};
  };
}

GLuint VplTransport::prepare(std::uint32_t vplCount) {
  return transport_.prepare(buffersFor(vplCount))[0];
}

double VplTransport::trace(const vk::TraceScene& scene, vk::TracePath path,
                           const vk::LightPathScene& surfaces, const vk::LightPathBatch& batch) {
  const std::array<std::uint64_t, 1> bytes{batch.vplCount * vk::kVplBytes};
  return transport_.trace(buffersFor(batch.vplCount), bytes, [&](bool useSemaphores) {
    tracer_.traceLightPaths(scene, path, surfaces, batch, useSemaphores);
  });
}

}  // namespace lgh
