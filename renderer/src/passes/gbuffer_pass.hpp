// G-buffer pass.
//   inputs:  GpuScene (meshes, materials, textures), camera matrices, how points and lines are
//            drawn (settings.primitives)
//   outputs: FrameTargets::gbuffer (position, normal, albedo, material, emissive, layers, depth)
//   shaders: glsl/gbuffer.vert, glsl/gbuffer.frag; lines and points through
//            glsl/gbuffer_lines.geom / glsl/gbuffer_points.geom, which widen them into screen-space
//            quads (every driver draws them the same, at any width)
#pragma once

#include <array>

#include "gl/gl_objects.hpp"
#include "lgh/request.hpp"
#include "passes/frame_targets.hpp"
#include "scene/camera.hpp"
#include "scene/gpu_scene.hpp"

namespace lgh {

class GBufferPass {
 public:
  GBufferPass();
  void run(const Scene& scene, const GpuScene& gpuScene, const CameraMatrices& camera,
           const PrimitiveSettings& primitives, FrameTargets& targets);

 private:
  void setMaterial(GLuint program, const Scene& scene, const GpuScene& gpuScene, int materialIndex,
                   bool unlit);
  void setFrameUniforms(GLuint program, const CameraMatrices& camera,
                        const PrimitiveSettings& primitives, const FrameTargets& targets,
                        bool disk);
  GLuint programFor(Topology topology) const;

  // Indexed by Topology: triangles, lines, points.
  std::array<gl::Program, 3> programs_;
};

}  // namespace lgh
