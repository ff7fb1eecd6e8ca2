#include "passes/forward_blend_pass.hpp"

#include <algorithm>
#include <set>
#include <vector>

#include <glm/glm.hpp>

#include "gl/slots.hpp"
#include "lgh/error.hpp"

namespace lgh {

bool ForwardBlendPass::needed(const MaterialTable& materials, const GpuScene& gpuScene) {
  return std::any_of(gpuScene.drawItems().begin(), gpuScene.drawItems().end(),
                     [&](const GpuScene::DrawItem& item) {
                       return materials.at(item.material).alphaMode == AlphaMode::Blend;
                     });
}

void ForwardBlendPass::bindTargets(FrameTargets& targets) {
  targets.sceneLinear();
  if (boundColor_ == targets.scene.texture.id() && boundDepth_ == targets.gbuffer.depth.id() &&
      boundWidth_ == targets.width && boundHeight_ == targets.height) {
    return;
  }
  framebuffer_ = gl::Framebuffer();
  glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, targets.scene.texture.id(), 0);
  glNamedFramebufferTexture(framebuffer_.id(), GL_DEPTH_ATTACHMENT, targets.gbuffer.depth.id(), 0);
  const GLenum status = glCheckNamedFramebufferStatus(framebuffer_.id(), GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw Error(ErrorCode::Internal,
                "framebuffer incomplete (status " + std::to_string(status) + ")", "forward blend");
  }
  boundColor_ = targets.scene.texture.id();
  boundDepth_ = targets.gbuffer.depth.id();
  boundWidth_ = targets.width;
  boundHeight_ = targets.height;
}

int ForwardBlendPass::run(const Inputs& inputs, SurfacePrograms& programs, GpuScene& gpuScene,
                          FrameTargets& targets) {
  struct Blended {
    const GpuScene::DrawItem* item;
    float distance;  // of its centre from the eye
  };
  const glm::vec3 eye = inputs.camera->position;
  std::vector<Blended> blended;
  for (const auto& item : gpuScene.drawItems()) {
    if (inputs.materials->at(item.material).alphaMode == AlphaMode::Blend) {
      blended.push_back({&item, glm::distance(GpuScene::centreOf(item), eye)});
    }
  }
  std::stable_sort(blended.begin(), blended.end(),
                   [](const Blended& a, const Blended& b) { return a.distance > b.distance; });
  bindTargets(targets);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, targets.width, targets.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glCullFace(GL_BACK);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_LIGHTS, inputs.lights);
  const SurfaceFrame frame{
      inputs.camera,  inputs.primitives,          targets.width, targets.height, inputs.lightCount,
      inputs.ambient, inputs.maxTessellationLevel};
  const bool disk = inputs.primitives->pointShape == PointShape::Disk;
  std::set<GLuint> prepared;
  SurfaceDrawState drawState;
  for (const Blended& entry : blended) {
    const GpuScene::DrawItem* item = entry.item;
    const Material& material = inputs.materials->at(item->material);
    const SurfaceProgramKey key = surfaceProgramKey(material, *item, true);
    SurfaceProgram& program = programs.get(key);
    if (prepared.insert(program.id()).second) {
      setSurfaceFrameUniforms(program, frame, item->topology == Topology::Points && disk);
    }
    glUseProgram(program.id());
    bindMaterial(program, material, gpuScene, item->unlit, drawState);
    drawSurface(program, *item, material, key.displaced, drawState);
  }
  glBindVertexArray(0);
  glFrontFace(GL_CCW);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDisable(GL_DEPTH_TEST);
  unbindMaterialSamplers();
  return static_cast<int>(blended.size());
}

}  // namespace lgh
