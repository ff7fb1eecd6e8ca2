// The light-source table of a frame on the GPU (gi_sources.hpp, glsl/include/gi_sources.glsl),
// uploaded only when it changes, and the uniforms that go with it. Shared by the light paths and
// the path-traced reference.
#pragma once

#include <vector>

#include "gi/gi_sources.hpp"
#include "gi/hit_geometry.hpp"
#include "gl/gl_objects.hpp"

namespace lgh {

class GiSourceBuffer {
 public:
  // The table of the frame's lights (in their buffer's order) and the scene's emissive triangles.
  const GiSourceTable& update(const std::vector<LightDesc>& lights, const HitGeometry& geometry,
                              const Scene& scene);
  const GiSourceTable& table() const { return table_; }
  // Binds the table and the frame's lights (their GpuLight SSBO) at their GI slots.
  void bind(GLuint lightBuffer) const;
  // uSourceCount and uSceneSphere of `program`.
  void setUniforms(GLuint program, const Scene& scene) const;

 private:
  GiSourceTable table_;
  gl::SizedBuffer buffer_;
  std::vector<GiSourceGpu> uploaded_;
};

// The scene's bounding sphere (xyz centre, w radius; directional lights shine through its disk).
glm::vec4 giSceneSphere(const Scene& scene);
// How far rays start off a surface: 1e-4 of the scene's diagonal, as the shadow rays.
float giSurfaceOffset(const Scene& scene);

}  // namespace lgh
