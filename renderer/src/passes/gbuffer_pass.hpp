// G-buffer pass.
//   inputs:  GpuScene (meshes, textures), the frame's materials (MaterialTable: the scene's with
//            the request's overrides), camera matrices, the analytic lights (Gouraud and flat
//            shading light vertices and primitives here; relief mapping's self-shadowing), how
//            points and lines are drawn (settings.primitives)
//   outputs: FrameTargets::gbuffer (position, normal, albedo, material, emissive, layers, depth);
//            blended surfaces (alphaMode BLEND) are left to ForwardBlendPass;
//            FrameTargets::surfaceTiles, the tiles its surfaces can cover (from the scene's bounds)
//   shaders: glsl/gbuffer.vert, glsl/gbuffer.frag (include/material_sampling.glsl); lines and
//            points through glsl/gbuffer_lines.geom / glsl/gbuffer_points.geom, which widen them
//            into screen-space quads; flat shading through glsl/gbuffer_flat.geom; displacement
//            through glsl/gbuffer_displace.tesc/.tese (passes/surface_programs.hpp)
// Only the position target (its w is the coverage every reader tests first) and the depth are
// cleared: the other targets are read only where something was drawn, and clearing them is a
// large share of the pass on GPUs with few graphics units (docs/BENCHMARKS.md). A frame whose
// surfaces need no layers target (no material layer, no classic model) does not write it, nor
// the emissive target where nothing emits (the direct lighting pass then does not read it).
// With a depth pre-pass (settings.depth_prepass) the surfaces are drawn twice: depth alone, then
// the targets with the depth test at LEQUAL and depth writes off, so each pixel's targets are
// written once. The same programs draw both times: GL's invariance rules then give the same
// depth values (only masks and the depth function differ between the two).
#pragma once

#include "gl/gl_objects.hpp"
#include "lgh/request.hpp"
#include "passes/frame_targets.hpp"
#include "passes/material_binding.hpp"
#include "passes/surface_programs.hpp"
#include "scene/camera.hpp"
#include "scene/gpu_scene.hpp"
#include "scene/material_table.hpp"

namespace lgh {

class GBufferPass {
 public:
  GBufferPass();
  struct Inputs {
    const MaterialTable* materials = nullptr;
    const CameraMatrices* camera = nullptr;
    const PrimitiveSettings* primitives = nullptr;
    GLuint lights = 0;  // SSBO of GpuLight
    int lightCount = 0;
    bool depthPrepass = false;      // settings.depth_prepass
    bool writeLayers = true;        // BrdfFeatures::usesLayersTarget()
    bool writeEmissive = true;      // surfacesEmit()
    bool clearEveryTarget = false;  // a probe reads the targets whole, background included
    // The world bounds of every surface drawn (Scene::bounds), from which the surface tiles
    // come; null: every tile.
    const Bounds* sceneBounds = nullptr;
  };
  void run(const Inputs& inputs, GpuScene& gpuScene, FrameTargets& targets);

  // The programs, shared with the forward pass.
  SurfacePrograms& programs() { return programs_; }
  float maxTessellationLevel() const { return maxTessellationLevel_; }

 private:
  // Picks the targets the frame writes (draw buffers) and clears the coverage and the depth.
  void prepareTargets(const Inputs& inputs, FrameTargets& targets);
  // The tiles the frame's surfaces can cover (passes/surface_tiles.hpp).
  static FrameTiles surfaceTilesOf(const Inputs& inputs, const GpuScene& gpuScene,
                                   const FrameTargets& targets);
  // One draw of every opaque surface, with the depth and colour state the caller set.
  void drawOpaque(const Inputs& inputs, GpuScene& gpuScene, const FrameTargets& targets);

  SurfacePrograms programs_;
  float maxTessellationLevel_ = 64.0F;
};

}  // namespace lgh
