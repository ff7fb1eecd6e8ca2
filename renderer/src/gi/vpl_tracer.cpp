#include "gi/vpl_tracer.hpp"

#include <algorithm>
#include <array>
#include <span>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "gi/gi_source_buffer.hpp"
#include "gi/gi_sources.hpp"
#include "gi/hit_geometry.hpp"
#include "lightgrid/lgh_types.hpp"

namespace lgh {
namespace {

constexpr GLuint kGroup = 64;          // local_size_x of the gi_*.comp kernels
constexpr GLuint kMaxGroupsX = 65535;  // the GL minimum of work groups along x
constexpr auto kVplBytes = static_cast<GLsizeiptr>(sizeof(PointLight));

template <typename T>
std::span<const std::byte> bytesOf(const std::vector<T>& values) {
  return std::as_bytes(std::span(values));
}

std::array<float, 3> arrayOf(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// The batch of one frame's light paths, in the GL kernels' terms (their uniforms).
vk::LightPathBatch lightPathBatch(const GiSettings& settings, const VplLayout& layout,
                                  const GiSourceTable& table, const std::vector<GpuLight>& lights,
                                  const Scene& scene) {
  const glm::vec4 sphere = giSceneSphere(scene);
  return {.paths = static_cast<std::uint32_t>(layout.paths),
          .vplCount = static_cast<std::uint32_t>(layout.count),
          .bounces = static_cast<std::uint32_t>(settings.bounces),
          .seed = settings.seed,
          .emissionSlot = layout.emissionSlot,
          .surfaceOffset = giSurfaceOffset(scene),
          .sceneSphere = {sphere.x, sphere.y, sphere.z, sphere.w},
          .sceneMin = arrayOf(scene.bounds.empty() ? glm::vec3(-1.0F) : scene.bounds.min),
          .sceneMax = arrayOf(scene.bounds.empty() ? glm::vec3(1.0F) : scene.bounds.max),
          .sourceCount = static_cast<std::uint32_t>(table.sources.size()),
          .sources = bytesOf(table.sources),
          .lights = bytesOf(lights)};
}

}  // namespace

void dispatchGi(std::uint32_t items) {
  const GLuint groups = std::max<GLuint>(1, (items + kGroup - 1) / kGroup);
  glDispatchCompute(std::min(groups, kMaxGroupsX), (groups + kMaxGroupsX - 1) / kMaxGroupsX, 1);
}

// Zeroes slots [from, count): the ones no path writes this frame.
void VplTracer::clearSlots(GLuint vpls, int from, int count) {
  if (count <= from) return;
  glClearNamedBufferSubData(vpls, GL_R32F, from * kVplBytes, (count - from) * kVplBytes, GL_RED,
                            GL_FLOAT, nullptr);
}

VplLayout VplTracer::generate(const VplTracingInputs& inputs, const CachedScene& cached,
                              GiTracing& tracing, gl::SizedBuffer& vpls, gl::GpuTimer& timer,
                              FrameReport& report) {
  traced_ = false;
  transferMs_ = 0.0;
  asBuildGpuMs_ = {};
  const GiSettings& settings = inputs.settings;
  const Scene& scene = cached.scene;
  VplLayout layout;
  layout.count = settings.vplCount;
  vpls.reserve(static_cast<GLsizeiptr>(std::max(layout.count, 1)) * kVplBytes);

  const GiTracing::Session session = tracing.begin(cached, inputs.tracing, "/settings/gi/enabled");
  asBuildGpuMs_ = session.asBuildGpuMs;
  const HitGeometry& geometry = HitGeometry::of(cached, inputs.materials);
  for (const std::string& warning : geometry.warnings()) report.warn(warning);
  const GiSourceTable table =
      buildGiSources(inputs.lights, geometry.emissiveTriangles(), scene.bounds);
  layout.emissionSlot = table.hasTriangles;
  layout.slotsPerPath = settings.bounces + (layout.emissionSlot ? 1 : 0);
  layout.paths = table.sources.empty() ? 0 : layout.count / layout.slotsPerPath;
  report.decide("gi_paths", std::to_string(layout.paths));
  report.decide("gi_slots_per_path", std::to_string(layout.slotsPerPath));
  report.decide("gi_tracing", std::string(enumName(session.path)));
  gl::ScopedGpuPass whole(timer, "gi vpls");
  if (layout.paths == 0) {
    clearSlots(vpls.id(), 0, layout.count);
    report.warn(table.sources.empty()
                    ? "gi: the frame has no light with power to trace: no indirect light"
                    : fmt::format("gi: vpl_count {} is below the {} slots of one light path: no "
                                  "indirect light",
                                  layout.count, layout.slotsPerPath));
    return layout;
  }
  // The frame's lights as the sources name them (their index in the frame's light buffer).
  lights_.clear();
  lights_.reserve(inputs.lights.size());
  for (const LightDesc& light : inputs.lights) lights_.push_back(packLight(light));
  const GLuint shared = session.vpls->prepare(static_cast<std::uint32_t>(layout.count));
  transferMs_ += tracing.traceLightPaths(session, geometry.lightPathScene(),
                                         lightPathBatch(settings, layout, table, lights_, scene));
  traced_ = true;
  bounces_ = settings.bounces;
  // Into the buffer the LGH build reads: a GPU copy (the shared buffer is the tracer's).
  glCopyNamedBufferSubData(shared, vpls.id(), 0, 0, layout.count * kVplBytes);
  report.decide("gi_transport", session.vpls->name());
  return layout;
}

void VplTracer::collectTimings(const GiTracing& tracing, FrameReport& report) {
  const bool traced = traced_;
  traced_ = false;
  report.lateRows.push_back([device = tracing.device(), mark = tracing.lightPathMark(), traced,
                             bounces = bounces_, asBuildGpuMs = asBuildGpuMs_,
                             transferMs = transferMs_](TimingTable& table) {
    if (const std::optional<double> ms = readBuildGpuMs(asBuildGpuMs)) {
      table.add("gi as build", TimingRow::Clock::Gpu, *ms);
    }
    if (!traced) return;
    // GL's span of the same name holds the submission where GL waits for it on the GPU (interop
    // semaphores); with staging copies it holds only the copy, and the submission's own span is
    // the generation. The frame's table keeps the larger (TimingTable::appendMerged).
    const std::optional<vk::LightPathTimings> vulkan =
        device != nullptr && mark.epoch != 0 ? device->lightPathTimings(mark) : std::nullopt;
    if (vulkan) {
      table.add("gi vpls", TimingRow::Clock::Gpu, vulkan->totalMs);
      table.add("gi emit", TimingRow::Clock::Gpu, vulkan->emitMs, 1);
      for (int bounce = 1; bounce <= bounces; ++bounce) {
        table.add(fmt::format("gi bounce {}", bounce), TimingRow::Clock::Gpu,
                  vulkan->bounceMs[static_cast<std::size_t>(bounce - 1)], 1);
      }
      table.add("gi rays", TimingRow::Clock::Gpu, vulkan->raysMs, 1);
    }
    table.add("gi transfer", TimingRow::Clock::Cpu, transferMs);
  });
}

}  // namespace lgh
