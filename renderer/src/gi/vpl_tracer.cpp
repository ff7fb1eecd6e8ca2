#include "gi/vpl_tracer.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "lgh/error.hpp"
#include "lightgrid/lgh_types.hpp"

namespace lgh {
namespace {

constexpr GLuint kGroup = 64;          // local_size_x of the gi_*.comp kernels
constexpr GLuint kMaxGroupsX = 65535;  // the GL minimum of work groups along x

void setUint(GLuint program, const char* name, std::uint32_t value) {
  glProgramUniform1ui(program, glGetUniformLocation(program, name), value);
}

void setPathUniforms(GLuint program, std::uint32_t paths, std::uint32_t seed, float offset) {
  setUint(program, "uPathCount", paths);
  setUint(program, "uSeed", seed);
  glProgramUniform1f(program, glGetUniformLocation(program, "uSurfaceOffset"), offset);
}

}  // namespace

void dispatchGi(std::uint32_t items) {
  const GLuint groups = std::max<GLuint>(1, (items + kGroup - 1) / kGroup);
  glDispatchCompute(std::min(groups, kMaxGroupsX), (groups + kMaxGroupsX - 1) / kMaxGroupsX, 1);
}

void insertNestedRow(TimingTable& table, const std::string& parent, TimingRow row) {
  auto it = std::find_if(table.rows.begin(), table.rows.end(),
                         [&](const TimingRow& existing) { return existing.name == parent; });
  if (it == table.rows.end()) {
    table.rows.push_back(std::move(row));
    return;
  }
  const int depth = it->depth;
  row.depth = depth + 1;
  ++it;
  while (it != table.rows.end() && it->depth > depth) ++it;
  table.rows.insert(it, std::move(row));
}

VplTracer::VplTracer()
    : emit_(gl::buildComputeProgram("gi_emit.comp")),
      bounce_(gl::buildComputeProgram("gi_bounce.comp")) {}
VplTracer::~VplTracer() = default;

// Zeroes slots [from, count): the ones no path writes this frame.
void VplTracer::clearSlots(GLuint vpls, int from, int count) {
  if (count <= from) return;
  constexpr auto kBytes = static_cast<GLintptr>(sizeof(PointLight));
  glClearNamedBufferSubData(vpls, GL_R32F, from * kBytes, (count - from) * kBytes, GL_RED, GL_FLOAT,
                            nullptr);
}

VplLayout VplTracer::generate(const VplTracingInputs& inputs, const CachedScene& cached,
                              GiTracing& tracing, gl::SizedBuffer& vpls, gl::GpuTimer& timer,
                              FrameReport& report) {
  traced_ = false;
  transferMs_ = 0.0;
  asBuildMs_ = -1.0;
  const GiSettings& settings = inputs.settings;
  const Scene& scene = cached.scene;
  VplLayout layout;
  layout.count = settings.vplCount;
  vpls.reserve(static_cast<GLsizeiptr>(std::max(layout.count, 1)) *
               static_cast<GLsizeiptr>(sizeof(PointLight)));

  const GiTracing::Session session = tracing.begin(cached, inputs.tracing, "/settings/gi/enabled");
  asBuildMs_ = session.asBuildMs;
  const HitGeometry& geometry = HitGeometry::of(cached, inputs.materials);
  for (const std::string& warning : geometry.warnings()) report.warn(warning);
  const GiSourceTable& table = sources_.update(inputs.lights, geometry, scene);
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
  const auto paths = static_cast<std::uint32_t>(layout.paths);
  clearSlots(vpls.id(), layout.paths * layout.slotsPerPath, layout.count);  // the left-over ones
  paths_.reserve(static_cast<GLsizeiptr>(paths) * 16);
  const HitBatchTransport::GlBuffers batch = session.transport->prepare(paths);
  const float offset = giSurfaceOffset(scene);

  geometry.bind();
  sources_.bind(inputs.lightBuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_PATHS, paths_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_VPLS, vpls.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_RAYS, batch.rays);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_HITS, batch.hits);
  {
    gl::ScopedGpuPass pass(timer, "gi emit");
    glUseProgram(emit_.id());
    sources_.setUniforms(emit_.id(), scene);
    setPathUniforms(emit_.id(), paths, settings.seed, offset);
    setUint(emit_.id(), "uEmissionSlots", layout.emissionSlot ? 1U : 0U);
    dispatchGi(paths);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }
  for (int bounce = 1; bounce <= settings.bounces; ++bounce) {
    transferMs_ += tracing.trace(session, {.rays = paths, .query = vk::HitQuery::Closest});
    traced_ = true;
    // The transport may have rebound nothing, but staging copies used the copy bindings.
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_RAYS, batch.rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_HITS, batch.hits);
    gl::ScopedGpuPass pass(timer, fmt::format("gi bounce {}", bounce));
    glUseProgram(bounce_.id());
    sources_.setUniforms(bounce_.id(), scene);
    setPathUniforms(bounce_.id(), paths, settings.seed, offset);
    setUint(bounce_.id(), "uBounce", static_cast<std::uint32_t>(bounce));
    setUint(bounce_.id(), "uLastBounce", bounce == settings.bounces ? 1U : 0U);
    setUint(bounce_.id(), "uSlot",
            static_cast<std::uint32_t>(bounce - 1 + (layout.emissionSlot ? 1 : 0)));
    dispatchGi(paths);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }
  glUseProgram(0);
  HitGeometry::unbind();
  report.decide("gi_transport", session.transport->name());
  return layout;
}

void VplTracer::collectTimings(GiTracing& tracing, TimingTable& table) {
  if (asBuildMs_ >= 0.0) table.add("gi as build", TimingRow::Clock::Gpu, asBuildMs_);
  if (!traced_) return;
  insertNestedRow(table, "gi vpls", {"gi rays", TimingRow::Clock::Gpu, tracing.collectGpuMs(), 0});
  table.add("gi transfer", TimingRow::Clock::Cpu, transferMs_);
  traced_ = false;
}

}  // namespace lgh
