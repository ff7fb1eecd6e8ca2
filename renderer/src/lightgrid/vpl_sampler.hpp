// Point lights for benchmarks and tests: N random points on the surfaces of a Scene, area
// weighted over every triangle of every instance (world space), each with an RGB intensity from
// its surface's base colour (factor x COLOR_0 x base-colour texture, nearest texel, linearised)
// times totalFlux / N. Deterministic for a seed: a 32-bit Mersenne Twister with our own float
// conversion, so the lights are the same on every platform.
#pragma once

#include <cstdint>
#include <vector>

#include "gl/gl_objects.hpp"
#include "lightgrid/lgh_types.hpp"
#include "scene/scene.hpp"

namespace lgh {

struct VplSamplerOptions {
  int count = 0;
  std::uint32_t seed = 1;
  float totalFlux = 1.0F;  // the sum of the lights' intensities is about totalFlux * albedo
};

// Throws lgh::Error(Invalid) when count > 0 and the scene has no triangle of non-zero area.
std::vector<PointLight> sampleSurfaceVpls(const Scene& scene, const VplSamplerOptions& options);

// Uploads into `buffer` (grown as needed). Checks every light on the CPU first and throws
// lgh::Error(Invalid) naming the first NaN/inf/out-of-range one.
void uploadPointLights(const std::vector<PointLight>& lights, gl::SizedBuffer& buffer);

}  // namespace lgh
