// An independent CPU reference of the many-light lighting, in double precision: the glTF 2.0
// metallic-roughness BRDF written from the specification (Appendix B: GGX distribution,
// height-correlated Smith visibility, Schlick Fresnel, Lambert diffuse) and summed over point
// lights with inverse-square falloff and a clamp of the distance, as the LGH's brute-force
// reference defines them. The GPU paths share one shading function (glsl/include/lgh_shading.glsl);
// this is the check that the function computes what the documents say.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "lightgrid/lgh_types.hpp"

namespace lgh {

struct CpuSurface {
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0, 1.0, 0.0};  // unit
  glm::dvec3 baseColor{1.0};         // linear
  double metallic = 0.0;
  double roughness = 1.0;  // perceptual; alpha = roughness^2
};

// f(l, v) max(n.l, 0): reflected radiance per unit irradiance from direction toLight.
glm::dvec3 cpuBrdfCosine(const CpuSurface& surface, const glm::dvec3& toViewer,
                         const glm::dvec3& toLight);

// sum_i I_i f(l_i, v) max(n.l_i, 0) / max(d_i^2, minDistance2).
glm::dvec3 cpuPointLightRadiance(const CpuSurface& surface, const glm::dvec3& viewer,
                                 const std::vector<PointLight>& lights, double minDistance2);

}  // namespace lgh
