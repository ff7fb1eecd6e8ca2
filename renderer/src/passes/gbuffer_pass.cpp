#include "passes/gbuffer_pass.hpp"

#include <algorithm>
#include <array>
#include <set>

#include "gl/slots.hpp"

namespace lgh {

GBufferPass::GBufferPass() {
  GLint level = 64;
  glGetIntegerv(GL_MAX_TESS_GEN_LEVEL, &level);
  maxTessellationLevel_ = static_cast<float>(level);
}

void GBufferPass::run(const Inputs& inputs, GpuScene& gpuScene, FrameTargets& targets) {
  targets.surfaceTiles = surfaceTilesOf(inputs, gpuScene, targets);
  glBindFramebuffer(GL_FRAMEBUFFER, targets.gbuffer.framebuffer.id());
  glViewport(0, 0, targets.width, targets.height);
  prepareTargets(inputs, targets);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glEnable(GL_FRAMEBUFFER_SRGB);  // the albedo target is sRGB-encoded
  glCullFace(GL_BACK);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_LIGHTS, inputs.lights);
  if (inputs.depthPrepass) {
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    drawOpaque(inputs, gpuScene, targets);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
  }
  drawOpaque(inputs, gpuScene, targets);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  glFrontFace(GL_CCW);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_FRAMEBUFFER_SRGB);
  unbindMaterialSamplers();
}

FrameTiles GBufferPass::surfaceTilesOf(const Inputs& inputs, const GpuScene& gpuScene,
                                       const FrameTargets& targets) {
  const FrameTiles all = allTiles(targets.width, targets.height);
  if (inputs.sceneBounds == nullptr) return all;
  // Displacement moves surfaces off the positions the bounds were taken over.
  const bool displaced =
      std::ranges::any_of(gpuScene.drawItems(), [&](const GpuScene::DrawItem& item) {
        return displacedMaterial(inputs.materials->at(item.material));
      });
  if (displaced) return all;
  const float margin = 0.5F * std::max(inputs.primitives->pointSize, inputs.primitives->lineWidth);
  return surfaceTiles(*inputs.sceneBounds, inputs.camera->viewProjection(), targets.width,
                      targets.height, margin);
}

void GBufferPass::prepareTargets(const Inputs& inputs, FrameTargets& targets) {
  // Draw buffer i is colour attachment i (passes/frame_targets.cpp); the last is the layers'.
  std::array<GLenum, 6> buffers{GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4, GL_COLOR_ATTACHMENT5};
  if (!inputs.writeEmissive && !inputs.clearEveryTarget) buffers[4] = GL_NONE;
  if (!inputs.writeLayers && !inputs.clearEveryTarget) buffers[5] = GL_NONE;
  if (buffers != targets.gbuffer.drawBuffers) {
    glNamedFramebufferDrawBuffers(targets.gbuffer.framebuffer.id(),
                                  static_cast<GLsizei>(buffers.size()), buffers.data());
    targets.gbuffer.drawBuffers = buffers;
  }
  const std::array<float, 4> zero{0, 0, 0, 0};
  glClearBufferfv(GL_COLOR, 0, zero.data());  // the coverage
  if (inputs.clearEveryTarget) {
    for (GLint i = 1; i < 5; ++i) glClearBufferfv(GL_COLOR, i, zero.data());
    const std::array<GLuint, 4> zeroBits{0, 0, 0, 0};
    glClearBufferuiv(GL_COLOR, 5, zeroBits.data());
  }
  const float farDepth = 1.0F;
  glClearBufferfv(GL_DEPTH, 0, &farDepth);
}

void GBufferPass::drawOpaque(const Inputs& inputs, GpuScene& gpuScene,
                             const FrameTargets& targets) {
  const SurfaceFrame frame{inputs.camera,        inputs.primitives, targets.width,
                           targets.height,       inputs.lightCount, 0.0F,
                           maxTessellationLevel_};
  const bool disk = inputs.primitives->pointShape == PointShape::Disk;
  std::set<GLuint> prepared;
  GLuint currentProgram = 0;
  int currentMaterial = -2;
  bool currentUnlit = false;
  SurfaceDrawState drawState;
  for (const auto& item : gpuScene.drawItems()) {
    const Material& material = inputs.materials->at(item.material);
    if (material.alphaMode == AlphaMode::Blend) continue;  // ForwardBlendPass draws these
    const SurfaceProgramKey key = surfaceProgramKey(material, item, false);
    SurfaceProgram& program = programs_.get(key);
    if (prepared.insert(program.id()).second) {
      setSurfaceFrameUniforms(program, frame, item.topology == Topology::Points && disk);
    }
    if (program.id() != currentProgram) {
      glUseProgram(program.id());
      currentProgram = program.id();
      currentMaterial = -2;
    }
    if (item.material != currentMaterial || item.unlit != currentUnlit) {
      bindMaterial(program, material, gpuScene, item.unlit, drawState);
      currentMaterial = item.material;
      currentUnlit = item.unlit;
    }
    drawSurface(program, item, material, key.displaced, drawState);
  }
}

}  // namespace lgh
