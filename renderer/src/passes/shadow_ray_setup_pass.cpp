#include "passes/shadow_ray_setup_pass.hpp"

#include "gl/shader_library.hpp"
#include "gl/slots.hpp"
#include "passes/direct_lighting_pass.hpp"
#include "passes/light_loops.hpp"

namespace lgh {
namespace {

GLint location(GLuint program, const char* name) { return glGetUniformLocation(program, name); }

}  // namespace

void setShadowRayUniforms(GLuint program, const ShadowRayLayout& layout) {
  glProgramUniform1i(program, location(program, "uShadowedLights"), layout.shadowedLights);
  glProgramUniform1i(program, location(program, "uLightSamples"), layout.lightSamples);
  glProgramUniform1i(program, location(program, "uRaysPerPixel"), layout.raysPerPixel());
  glProgramUniform1i(program, location(program, "uVisibilityWords"), layout.words());
}

ShadowRaySetupPass::ShadowRaySetupPass(bool clearsOrigins, bool unrollsLightLoops)
    : clearsOrigins_(clearsOrigins), unrollsLightLoops_(unrollsLightLoops) {
  // A GPU's one program, compiled up front as it always was; a CPU rasteriser's are compiled for
  // the layouts its frames bring.
  if (!unrollsLightLoops_) program(ShadowRayLayout{});
}

GLuint ShadowRaySetupPass::program(const ShadowRayLayout& layout) {
  std::string defines = unrollsLightLoops_ ? shadowLayoutDefines(layout) : std::string();
  auto found = programs_.find(defines);
  if (found == programs_.end()) {
    gl::Program built = gl::buildComputeProgram("shadow_ray_setup.comp", defines);
    found = programs_.emplace(std::move(defines), std::move(built)).first;
  }
  return found->second.id();
}

// On a CPU rasteriser every pixel's origin goes to (0, 0, 0, 0), no surface, by a clear, and the
// shader stores the origins of surfaces only (glsl/shadow_ray_setup.comp): there a shader's store
// is a scalar loop over the SIMD lanes and a clear a fill, while on a GPU the clear costs more.
void ShadowRaySetupPass::prepareOrigins(GLuint program, GLuint origins,
                                        const FrameTargets& frame) const {
  if (clearsOrigins_) {
    const auto bytes = static_cast<GLsizeiptr>(frame.width) * frame.height * 4 * sizeof(float);
    glClearNamedBufferSubData(origins, GL_RGBA32F, 0, bytes, GL_RGBA, GL_FLOAT, nullptr);
  }
  glProgramUniform1i(program, location(program, "uOriginsCleared"), clearsOrigins_ ? 1 : 0);
}

FrameTiles ShadowRaySetupPass::tilesToRun(const FrameTargets& frame) const {
  return clearsOrigins_ ? frame.tilesWithSurfaces() : allTiles(frame.width, frame.height);
}

void ShadowRaySetupPass::run(const ShadowRaySetupInputs& inputs, const FrameTargets& frame,
                             GLuint origins, GLuint targets) {
  const GLuint program = this->program(inputs.layout);
  glUseProgram(program);
  setShadowRayUniforms(program, inputs.layout);
  glProgramUniform2i(program, location(program, "uFrameSize"), frame.width, frame.height);
  glProgramUniform1i(program, location(program, "uLghSampleCount"), inputs.layout.lghSamples);
  glProgramUniform1f(program, location(program, "uSurfaceOffset"), inputs.surfaceOffset);
  glProgramUniform1ui(program, location(program, "uSeed"), inputs.seed);
  bindGBuffer(frame.gbuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_LIGHTS, inputs.lights);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_SAMPLES, inputs.lghSamples);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_RAY_ORIGINS, origins);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_RAY_TARGETS, targets);
  prepareOrigins(program, origins, frame);
  dispatchTiles(program, tilesToRun(frame));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void ShadowRaySetupPass::runToPointLights(GLuint pointLights, int first, int count,
                                          float surfaceOffset, const FrameTargets& frame,
                                          GLuint origins, GLuint targets) {
  if (pointLightProgram_.id() == 0) {
    pointLightProgram_ =
        gl::buildComputeProgram("shadow_ray_setup.comp", "#define LGH_POINT_LIGHT_RAYS 1\n");
  }
  const GLuint program = pointLightProgram_.id();
  glUseProgram(program);
  ShadowRayLayout layout;
  layout.lghSamples = count;  // rays per pixel; the shader writes them as point-light targets
  setShadowRayUniforms(program, layout);
  glProgramUniform2i(program, location(program, "uFrameSize"), frame.width, frame.height);
  glProgramUniform1i(program, location(program, "uFirstLight"), first);
  glProgramUniform1f(program, location(program, "uSurfaceOffset"), surfaceOffset);
  bindGBuffer(frame.gbuffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_POINT_LIGHTS, pointLights);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_RAY_ORIGINS, origins);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_RAY_TARGETS, targets);
  prepareOrigins(program, origins, frame);
  dispatchTiles(program, tilesToRun(frame));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace lgh
