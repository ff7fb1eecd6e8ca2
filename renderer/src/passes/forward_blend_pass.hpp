// Forward pass of blended surfaces (glTF alphaMode BLEND), after the composite into the linear
// scene target and before the display pass.
//   inputs:  GpuScene, the frame's materials, camera, the analytic lights and the ambient term,
//            the G-buffer's depth (blended surfaces hide behind opaque ones, and write no depth)
//   outputs: FrameTargets::scene (linear light, rows as GL stores them), blended "over" (colour by
//   alpha, coverage accumulated in alpha) shaders: the surface programs' forward variants:
//   glsl/gbuffer.vert [+ geometry/tessellation
//            stages] + glsl/forward_blend.frag (the G-buffer pass's material sampling, the direct
//            lighting's light terms)
// Surfaces are sorted back to front by the distance of their bounds' centres from the camera: per
// draw item, not per triangle, so intersecting or self-overlapping blended meshes may blend out of
// order.
#pragma once

#include "gl/gl_objects.hpp"
#include "passes/frame_targets.hpp"
#include "passes/material_binding.hpp"
#include "passes/surface_programs.hpp"
#include "scene/material_table.hpp"

namespace lgh {

class ForwardBlendPass {
 public:
  struct Inputs {
    const MaterialTable* materials = nullptr;
    const CameraMatrices* camera = nullptr;
    const PrimitiveSettings* primitives = nullptr;
    GLuint lights = 0;  // SSBO of GpuLight
    int lightCount = 0;
    float ambient = 0.0F;
    float maxTessellationLevel = 64.0F;
  };

  // Whether the frame has blended surfaces at all (the pass and its timing row are skipped
  // otherwise).
  static bool needed(const MaterialTable& materials, const GpuScene& gpuScene);

  // Returns how many draw items were blended.
  int run(const Inputs& inputs, SurfacePrograms& programs, GpuScene& gpuScene,
          FrameTargets& targets);

 private:
  void bindTargets(FrameTargets& targets);

  gl::Framebuffer framebuffer_;
  GLuint boundColor_ = 0;
  GLuint boundDepth_ = 0;
  int boundWidth_ = 0;  // a resize may hand out the old names again
  int boundHeight_ = 0;
};

}  // namespace lgh
