#include "gi/path_traced_reference.hpp"

#include <algorithm>

#include <glm/gtc/type_ptr.hpp>

#include "gi/hit_geometry.hpp"
#include "gi/vpl_tracer.hpp"
#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "passes/direct_lighting_pass.hpp"

namespace lgh {
namespace {

// Paths of one iteration at most (the batch buffers hold 64 bytes a ray).
constexpr std::uint32_t kMaxPathsPerIteration = 1U << 20;
constexpr GLsizeiptr kPathBytes = 96;  // GiCameraPath

void setUint(GLuint program, const char* name, std::uint32_t value) {
  glProgramUniform1ui(program, glGetUniformLocation(program, name), value);
}

void setCommon(GLuint program, std::uint32_t paths, std::uint32_t samples, std::uint32_t seed,
               float offset) {
  setUint(program, "uPathCount", paths);
  setUint(program, "uSamples", samples);
  setUint(program, "uSeed", seed);
  glProgramUniform1f(program, glGetUniformLocation(program, "uSurfaceOffset"), offset);
}

void barrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT); }

// The seed of iteration `iteration`.
std::uint32_t iterationSeed(std::uint32_t seed, std::uint32_t iteration) {
  std::uint32_t state = (seed ^ 0x85ebca6bU) * 747796405U + iteration * 2891336453U + 1U;
  state ^= state >> 16;
  return state * 0x7feb352dU;
}

}  // namespace

PathTracedReference::PathTracedReference()
    : start_(gl::buildComputeProgram("gi_path_start.comp")),
      gather_(gl::buildComputeProgram("gi_path_gather.comp")),
      vertex_(gl::buildComputeProgram("gi_path_vertex.comp")),
      accumulate_(gl::buildComputeProgram("gi_path_accumulate.comp")) {}
PathTracedReference::~PathTracedReference() = default;

FloatImage PathTracedReference::render(const PathTracingSettings& settings,
                                       const PathTracingInputs& inputs, GiTracing& tracing) {
  const FrameTargets& frame = inputs.frame;
  const auto pixels = static_cast<std::uint32_t>(frame.width * frame.height);
  const GiTracing::Session session =
      tracing.begin(inputs.scene, settings.tracing, "/settings/gi/enabled");
  const auto spp = static_cast<std::uint32_t>(std::max(settings.samplesPerPixel, 1));
  const std::uint32_t samples =
      std::clamp<std::uint32_t>(kMaxPathsPerIteration / std::max(pixels, 1U), 1U, spp);
  const std::uint32_t iterations = (spp + samples - 1) / samples;
  const std::uint32_t paths = pixels * samples;
  paths_.reserve(static_cast<GLsizeiptr>(paths) * kPathBytes);
  radiance_.reserve(static_cast<GLsizeiptr>(pixels) * 16);
  glClearNamedBufferData(radiance_.id(), GL_R32F, GL_RED, GL_FLOAT, nullptr);
  const GiSourceTable& table = sources_.update(
      inputs.lights, HitGeometry::of(inputs.scene, inputs.materials), inputs.scene.scene);
  for (std::uint32_t i = 0; i < iterations && !table.sources.empty(); ++i) {
    iterate(settings, inputs, tracing, session, paths, samples, iterationSeed(settings.seed, i));
  }
  tracing.collectGpuMs();

  std::vector<glm::vec4> sums(pixels);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(radiance_.id(), 0, static_cast<GLsizeiptr>(pixels) * 16, sums.data());
  FloatImage image;
  image.width = frame.width;
  image.height = frame.height;
  image.rgba.resize(static_cast<std::size_t>(pixels) * 4);
  const float scale = 1.0F / static_cast<float>(iterations * samples);
  for (int y = 0; y < frame.height; ++y) {  // GL rows run bottom-up, images top-down
    for (int x = 0; x < frame.width; ++x) {
      const glm::vec4 sum = sums[static_cast<std::size_t>(y) * frame.width + x];
      float* out =
          &image.rgba[(static_cast<std::size_t>(frame.height - 1 - y) * frame.width + x) * 4];
      out[0] = sum.r * scale;
      out[1] = sum.g * scale;
      out[2] = sum.b * scale;
      out[3] = sum.a;
    }
  }
  return image;
}

void PathTracedReference::iterate(const PathTracingSettings& settings,
                                  const PathTracingInputs& inputs, GiTracing& tracing,
                                  const GiTracing::Session& session, std::uint32_t paths,
                                  std::uint32_t samples, std::uint32_t seed) {
  const Scene& scene = inputs.scene.scene;
  const FrameTargets& frame = inputs.frame;
  const float offset = giSurfaceOffset(scene);
  const HitBatchTransport::GlBuffers batch = session.transport->prepare(paths);
  const auto bind = [&] {
    HitGeometry::of(inputs.scene, inputs.materials).bind();
    sources_.bind(inputs.lightBuffer);
    bindGBuffer(frame.gbuffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_PATHS, paths_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_RADIANCE, radiance_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_RAYS, batch.rays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_HITS, batch.hits);
  };
  const auto run = [&](const gl::Program& program, std::uint32_t items) {
    bind();
    glUseProgram(program.id());
    sources_.setUniforms(program.id(), scene);
    setCommon(program.id(), paths, samples, seed, offset);
    dispatchGi(items);
    barrier();
  };
  const auto trace = [&](vk::HitQuery query) {
    tracing.trace(session, {.rays = paths, .query = query});
  };

  glProgramUniform2i(start_.id(), glGetUniformLocation(start_.id(), "uFrameSize"), frame.width,
                     frame.height);
  glProgramUniform3fv(start_.id(), glGetUniformLocation(start_.id(), "uCameraPosition"), 1,
                      glm::value_ptr(inputs.camera.position));
  run(start_, paths);
  trace(vk::HitQuery::Any);
  for (int vertex = 1; vertex <= settings.bounces; ++vertex) {
    setUint(gather_.id(), "uLastVertex", 0U);
    run(gather_, paths);
    trace(vk::HitQuery::Closest);
    setUint(vertex_.id(), "uVertex", static_cast<std::uint32_t>(vertex));
    run(vertex_, paths);
    trace(vk::HitQuery::Any);
  }
  setUint(gather_.id(), "uLastVertex", 1U);
  run(gather_, paths);
  glProgramUniform2i(accumulate_.id(), glGetUniformLocation(accumulate_.id(), "uFrameSize"),
                     frame.width, frame.height);
  run(accumulate_, static_cast<std::uint32_t>(frame.width * frame.height));
  glUseProgram(0);
  HitGeometry::unbind();
}

}  // namespace lgh
