// Synthetic point-light sets for tests (seeded, deterministic): uniform in a box, Gaussian
// clusters, on a plane, and on the vertices of a lattice. Intensities are random colours scaled so
// the set's total luminance is about `flux`.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "lightgrid/lgh_types.hpp"

namespace lgh {

std::vector<PointLight> uniformLights(int count, glm::vec3 lo, glm::vec3 hi, std::uint32_t seed,
                                      float flux = 1.0F);
// `clusters` Gaussian blobs of standard deviation `sigma` with centres uniform in [lo, hi].
std::vector<PointLight> clusteredLights(int count, int clusters, float sigma, glm::vec3 lo,
                                        glm::vec3 hi, std::uint32_t seed, float flux = 1.0F);
// Uniform on the plane through `origin` spanned by u and v (coefficients in [0, 1)).
std::vector<PointLight> planeLights(int count, glm::vec3 origin, glm::vec3 u, glm::vec3 v,
                                    std::uint32_t seed, float flux = 1.0F);
// One light on every point origin + spacing * (i, j, k), 0 <= i,j,k < n.
std::vector<PointLight> latticeLights(int n, glm::vec3 origin, float spacing, std::uint32_t seed,
                                      float flux = 1.0F);

// Sum of the lights' rgb intensities (double precision).
glm::dvec3 totalIntensity(const std::vector<PointLight>& lights);

}  // namespace lgh
