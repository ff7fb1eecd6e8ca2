// LGH raster lighting (Lin & Yuksel 2019, Sec. 3.2-3.3 and 4.3): the paper's light rasterization.
//   inputs:  the hierarchy (grid lights, level table), the G-buffer - or, interleaved, the tile
//            G-buffer of LghInterleavePass::split - with its depth, camera
//   outputs: LghLightingTargets: radiance accumulated additively into the RGBA32F atlas, the
//            per-pixel reservoir sum F and k shadow samples (final form after the resolve), the
//            overdraw counter when asked; without interleaving also FrameTargets::indirect
//   shaders: glsl/lgh_interleave_commands.comp (per-tile indirect draws), glsl/lgh_light_volume.*
//            (levels below the top: one instanced draw of cubes bounding radius 2 r_l, back faces
//            depth-tested against the surface), glsl/fullscreen.vert + glsl/lgh_top_level.frag (top
//            level), glsl/lgh_resolve.comp (samples; radiance copy into the RGBA16F target)
#pragma once

#include "gl/gl_objects.hpp"
#include "passes/frame_targets.hpp"
#include "passes/lgh_lighting_common.hpp"
#include "scene/camera.hpp"

namespace lgh {

class LghRasterLightingPass {
 public:
  LghRasterLightingPass();
  void run(const LghHierarchyBuffers& hierarchy, const LghLightingParams& params,
           const CameraMatrices& camera, FrameTargets& frame, LghLightingTargets& targets);

  enum class LockMode { None, Interlock, SpinLock };
  // The lock a locked reservoir uses on this device: fragment shader interlock where available.
  LockMode lockMode(bool locked) const;

  // Maps the full frame's pixel centres onto tile (tx, ty)'s, in clip space:
  // clip.xy = clip.xy * result.xy + result.zw * clip.w (identity without interleaving).
  static glm::vec4 tileTransform(int tileX, int tileY, const LghLightingTargets& targets);

 private:
  void writeDrawCommands(const LghLightingParams& params, const LghLightingTargets& targets);
  void drawLightVolumes(const LghLightingParams& params, const CameraMatrices& camera,
                        LghLightingTargets& targets);
  void drawTopLevel(const LghLightingParams& params, const CameraMatrices& camera,
                    LghLightingTargets& targets);
  void resolve(const LghLightingParams& params, const CameraMatrices& camera, FrameTargets& frame,
               LghLightingTargets& targets);
  std::string fragmentDefines(const LghLightingParams& params) const;

  bool interlockAvailable_ = false;
  ProgramCache volumePrograms_;
  ProgramCache topPrograms_;
  ProgramCache resolvePrograms_;
  ProgramCache commandPrograms_;
  gl::SizedBuffer tileDraws_;
  gl::VertexArray emptyVertexArray_;
};

}  // namespace lgh
