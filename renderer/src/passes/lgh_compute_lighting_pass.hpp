// LGH compute lighting: the hierarchy of the raster path evaluated by compute shaders, for GPUs
// whose rasterizers are weak next to their compute units (Hopper; docs/ARCHITECTURE.md).
//   inputs:  the hierarchy (grid lights, level table), the full-resolution G-buffer, camera
//   outputs: radiance into FrameTargets::indirect (no interleaving) or the RGBA32F tile atlas of
//            LghLightingTargets (interleaved, for the shared compositing pass), the reservoir sum
//            F, the k final shadow samples, the overdraw counter (lights evaluated) when asked
//   shaders: glsl/lgh_lighting.comp (8x8-pixel blocks: bounding box, per-level culling of the
//            grid lights by binary search over the vertex-sorted levels, shared-memory batches,
//            the same blending, BRDF and reservoir code as the raster path)
#pragma once

#include "gl/gl_objects.hpp"
#include "passes/frame_targets.hpp"
#include "passes/lgh_lighting_common.hpp"
#include "scene/camera.hpp"

namespace lgh {

class LghComputeLightingPass {
 public:
  void run(const LghHierarchyBuffers& hierarchy, const LghLightingParams& params,
           const CameraMatrices& camera, FrameTargets& frame, LghLightingTargets& targets);

 private:
  ProgramCache programs_;
};

}  // namespace lgh
