// The light sources of the light paths (CPU half of glsl/include/gi_sources.glsl): the frame's
// analytic lights (point, spot, directional; the direct lighting's own lights, which the sources
// name by index) and the scene's emissive triangles, each with its emitted power and a
// cumulative selection probability proportional to the power's luminance (docs/GI.md).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gi/hit_geometry.hpp"
#include "lgh/request.hpp"
#include "scene/scene.hpp"

namespace lgh {

struct GiSourceGpu {        // GiSource, 112 bytes
  glm::ivec4 info{0};       // x: kind (0 light, 1 triangle), y: light index, z: double-sided
  glm::vec4 vertex0{0.0F};  // w: area
  glm::vec4 edge1{0.0F};
  glm::vec4 edge2{0.0F};
  glm::vec4 normal{0.0F};
  glm::vec4 radiance{0.0F};
  glm::vec4 power{0.0F};  // rgb power, w: cumulative probability
};
static_assert(sizeof(GiSourceGpu) == 112, "GiSourceGpu must match GiSource (std430)");

inline constexpr int kGiSourceLight = 0;
inline constexpr int kGiSourceTriangle = 1;

struct GiSourceTable {
  std::vector<GiSourceGpu> sources;  // with zero-power sources left out
  bool hasTriangles = false;         // some emissive triangle emits
  double totalPower = 0.0;           // luminance of the summed power
};

// The emitted power of an analytic light: point 4 pi I, spot 2 pi (1 - cos outer) I (the cone it
// shines into), directional E times the projected area of the scene's bounding box (what its
// paths start on); I and E are colour x intensity (the diffuse colour where the light sets one).
glm::vec3 lightPower(const LightDesc& light, const Bounds& sceneBounds);

// `lights`: the frame's lights in the order of its light buffer.
GiSourceTable buildGiSources(const std::vector<LightDesc>& lights,
                             const std::vector<EmissiveTriangle>& triangles,
                             const Bounds& sceneBounds);

}  // namespace lgh
