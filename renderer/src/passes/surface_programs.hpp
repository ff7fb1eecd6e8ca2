// The programs that draw scene surfaces (the G-buffer pass and the forward pass of blended
// surfaces), one per combination of
//   topology  triangles; lines and points through gbuffer_lines.geom / gbuffer_points.geom
//   shading   pixel; Gouraud (gbuffer.vert lights the vertices, LGH_GOURAUD); flat
//             (gbuffer_flat.geom lights each triangle)
//   displaced displacement mapping (gbuffer_displace.tesc/.tese, drawn as GL_PATCHES)
//   forward   gbuffer.frag or forward_blend.frag
//   features  what the material can need (LGH_MATERIAL_FEATURES of
//             glsl/include/material_sampling.glsl); the forward pass keeps the generic shader
// built on first use: most frames need two or three of them.
#pragma once

#include <cstdint>
#include <map>
#include <tuple>
#include <utility>

#include "gl/gl_objects.hpp"
#include "gl/uniform_locations.hpp"
#include "lgh/material_settings.hpp"
#include "scene/scene.hpp"

namespace lgh {

// The LGH_MATERIAL_* bits of glsl/include/material_sampling.glsl.
inline constexpr std::uint32_t kMaterialDiscard = 1U;
inline constexpr std::uint32_t kMaterialHeight = 2U;
inline constexpr std::uint32_t kMaterialLayers = 4U;
inline constexpr std::uint32_t kMaterialClassic = 8U;
inline constexpr std::uint32_t kMaterialBicubic = 16U;
inline constexpr std::uint32_t kMaterialSurfaceFrame = 32U;
inline constexpr std::uint32_t kAllMaterialFeatures = 63U;

struct SurfaceProgramKey {
  Topology topology = Topology::Triangles;
  ShadingMode shading = ShadingMode::Pixel;
  bool displaced = false;
  bool forward = false;
  std::uint32_t features = kAllMaterialFeatures;
  bool operator<(const SurfaceProgramKey& other) const {
    return std::tie(topology, shading, displaced, forward, features) <
           std::tie(other.topology, other.shading, other.displaced, other.forward, other.features);
  }
};

// A linked variant and its uniform locations, looked up on first use.
struct SurfaceProgram {
  explicit SurfaceProgram(gl::Program linked)
      : program(std::move(linked)), uniforms(program.id()) {}
  GLuint id() const { return program.id(); }
  gl::Program program;
  gl::UniformLocations uniforms;
};

class SurfacePrograms {
 public:
  // Builds the variant on first use; throws lgh::Error(Internal) with the driver's log. The
  // reference stays valid as long as this object.
  SurfaceProgram& get(const SurfaceProgramKey& key);

 private:
  std::map<SurfaceProgramKey, SurfaceProgram> programs_;
};

}  // namespace lgh
