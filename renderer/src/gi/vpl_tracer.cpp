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

constexpr GLuint kGroup = 64;            // local_size_x of gi_emit.comp and gi_bounce.comp
constexpr GLuint kMaxGroupsX = 65535;    // the GL minimum of work groups along x
constexpr float kSurfaceOffset = 1e-4F;  // of the scene's diagonal, as the shadow rays

struct Dispatch {
  GLuint x = 1;
  GLuint y = 1;
};

// Work groups for `items` invocations of kGroup, 2D beyond kMaxGroupsX groups.
Dispatch dispatchFor(std::uint32_t items) {
  const GLuint groups = std::max<GLuint>(1, (items + kGroup - 1) / kGroup);
  return {std::min(groups, kMaxGroupsX), (groups + kMaxGroupsX - 1) / kMaxGroupsX};
}

void dispatch(std::uint32_t items) {
  const Dispatch groups = dispatchFor(items);
  glDispatchCompute(groups.x, groups.y, 1);
}

void setUint(GLuint program, const char* name, std::uint32_t value) {
  glProgramUniform1ui(program, glGetUniformLocation(program, name), value);
}

float sceneDiagonal(const Scene& scene) {
  return scene.bounds.empty() ? 1.0F : glm::length(scene.bounds.size());
}

glm::vec4 sceneSphere(const Scene& scene) {
  if (scene.bounds.empty()) return {0.0F, 0.0F, 0.0F, 1.0F};
  return {scene.bounds.center(), std::max(0.5F * sceneDiagonal(scene), 1e-6F)};
}

void setSourceUniforms(GLuint program, const Scene& scene, std::size_t sources, std::uint32_t paths,
                       std::uint32_t seed, float offset) {
  setUint(program, "uSourceCount", static_cast<std::uint32_t>(sources));
  const glm::vec4 sphere = sceneSphere(scene);
  glProgramUniform4f(program, glGetUniformLocation(program, "uSceneSphere"), sphere.x, sphere.y,
                     sphere.z, sphere.w);
  setUint(program, "uPathCount", paths);
  setUint(program, "uSeed", seed);
  glProgramUniform1f(program, glGetUniformLocation(program, "uSurfaceOffset"), offset);
}

}  // namespace

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

void VplTracer::uploadSources(const GiSourceTable& table) {
  const std::size_t bytes = table.sources.size() * sizeof(GiSourceGpu);
  if (table.sources.size() == uploaded_.size() &&
      std::memcmp(table.sources.data(), uploaded_.data(), bytes) == 0) {
    return;
  }
  sources_.reserve(static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, sizeof(GiSourceGpu))));
  if (bytes > 0) {
    glNamedBufferSubData(sources_.id(), 0, static_cast<GLsizeiptr>(bytes), table.sources.data());
  }
  uploaded_ = table.sources;
}

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
  const HitGeometry& geometry = HitGeometry::of(cached);
  for (const std::string& warning : geometry.warnings()) report.warn(warning);
  const float sceneRadius = sceneSphere(scene).w;
  const GiSourceTable table =
      buildGiSources(inputs.lights, geometry.emissiveTriangles(), sceneRadius);
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
  uploadSources(table);
  paths_.reserve(static_cast<GLsizeiptr>(paths) * 16);
  const HitBatchTransport::GlBuffers batch = session.transport->prepare(paths);
  const float offset = std::max(kSurfaceOffset * sceneDiagonal(scene), 1e-6F);

  geometry.bind();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_SOURCES, sources_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_LIGHTS, inputs.lightBuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_PATHS, paths_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_VPLS, vpls.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_RAYS, batch.rays);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_HITS, batch.hits);
  {
    gl::ScopedGpuPass pass(timer, "gi emit");
    glUseProgram(emit_.id());
    setSourceUniforms(emit_.id(), scene, table.sources.size(), paths, settings.seed, offset);
    setUint(emit_.id(), "uEmissionSlots", layout.emissionSlot ? 1U : 0U);
    dispatch(paths);
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
    setSourceUniforms(bounce_.id(), scene, table.sources.size(), paths, settings.seed, offset);
    setUint(bounce_.id(), "uBounce", static_cast<std::uint32_t>(bounce));
    setUint(bounce_.id(), "uLastBounce", bounce == settings.bounces ? 1U : 0U);
    setUint(bounce_.id(), "uSlot",
            static_cast<std::uint32_t>(bounce - 1 + (layout.emissionSlot ? 1 : 0)));
    dispatch(paths);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    GL_COMMAND_BARRIER_BIT);
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
