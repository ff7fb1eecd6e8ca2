// Interleaved sampling (Lin & Yuksel 2019, Sec. 4.3), both ends of it.
// split (raster path only):
//   inputs:  FrameTargets::gbuffer (position, normal, albedo, material, depth)
//   outputs: LghLightingTargets::tiles: the same G-buffer rearranged into n x n low-resolution
//            tiles (full-resolution pixel p in tile p mod n, at p / n)
//   shaders: glsl/fullscreen.vert, glsl/lgh_interleave_split.frag
// composite (both paths; the compute path writes the same tile atlas as the raster path):
//   inputs:  LghLightingTargets::accumulation (the lit tile atlas), FrameTargets::gbuffer, camera
//   outputs: FrameTargets::indirect (RGBA16F): each pixel's own tile plus the other tiles'
//            lighting gathered from geometrically matching neighbours
//   shaders: glsl/lgh_interleave_composite.comp
#pragma once

#include "gl/gl_objects.hpp"
#include "passes/frame_targets.hpp"
#include "passes/lgh_lighting_common.hpp"
#include "scene/camera.hpp"

namespace lgh {

class LghInterleavePass {
 public:
  void split(const LghLightingParams& params, const CameraMatrices& camera, FrameTargets& frame,
             LghLightingTargets& targets);
  void composite(const LghLightingParams& params, const CameraMatrices& camera, FrameTargets& frame,
                 LghLightingTargets& targets);

 private:
  ProgramCache splitProgram_;
  ProgramCache compositeProgram_;
  gl::VertexArray emptyVertexArray_;
};

}  // namespace lgh
