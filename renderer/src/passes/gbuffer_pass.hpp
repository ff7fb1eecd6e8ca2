// G-buffer pass.
//   inputs:  GpuScene (meshes, materials, textures), camera matrices
//   outputs: FrameTargets::gbuffer (position, normal, albedo, material, emissive, depth)
//   shaders: glsl/gbuffer.vert, glsl/gbuffer.frag
#pragma once

#include "gl/gl_objects.hpp"
#include "passes/frame_targets.hpp"
#include "scene/camera.hpp"
#include "scene/gpu_scene.hpp"

namespace lgh {

class GBufferPass {
 public:
  GBufferPass();
  void run(const Scene& scene, const GpuScene& gpuScene, const CameraMatrices& camera,
           FrameTargets& targets);

 private:
  void setMaterial(const Scene& scene, const GpuScene& gpuScene, int materialIndex);
  gl::Program program_;
  GLint worldLocation_, normalMatrixLocation_, viewProjectionLocation_;
};

}  // namespace lgh
