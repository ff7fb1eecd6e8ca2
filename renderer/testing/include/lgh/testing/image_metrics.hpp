// Error metrics between a rendered image and a reference (e.g. the brute-force many-light image).
#pragma once

#include <vector>

#include <glm/vec2.hpp>

#include "lgh/image.hpp"

namespace lgh {

struct ImageError {
  // sqrt(sum |a - r|^2 / sum |r|^2) over RGB of covered pixels: the relative RMSE the LGH issue
  // reports (0 = identical; scale-free, so HDR radiance needs no tone mapping first).
  double relativeRmse = 0.0;
  // 10 log10(peak^2 / MSE) with peak = the reference's maximum RGB value; +inf when identical.
  double psnr = 0.0;
  double rmse = 0.0;
  std::size_t pixels = 0;  // pixels compared (alpha > 0 in the reference)
};

// Compares RGB where the reference's alpha is > 0. Throws lgh::Error(Invalid) on a size mismatch.
ImageError compareToReference(const FloatImage& image, const FloatImage& reference);

// The error report of the GI and LGH benchmarks and tests (docs/GI.md, "Metrics"): the relative
// RMSE over all covered pixels and per material class, and the brightness bias, the ratio of the
// summed luminance minus 1 (> 0: too bright), which the relative RMSE cannot tell from noise.
struct MaterialErrors {
  ImageError all;
  ImageError diffuse;  // the other pixels
  ImageError glossy;   // metallic > 0.5 or roughness < 0.5: where reflections of single lights show
  double bias = 0.0;
  double diffuseBias = 0.0;
  double glossyBias = 0.0;
  double glossyFraction = 0.0;  // of the compared pixels
};

bool isGlossyPixel(const glm::vec2& metallicRoughness);

// `metallicRoughness`: per pixel, top row first (LghFrameProbe::metallicRoughness).
MaterialErrors compareByMaterial(const FloatImage& image, const FloatImage& reference,
                                 const std::vector<glm::vec2>& metallicRoughness);

// RGB of `image` times the red channel of `factor` (the LGH's indirect light times its filtered
// shadow ratio: the shadowed indirect light of the frame); alpha from `image`.
FloatImage multiplied(const FloatImage& image, const FloatImage& factor);

}  // namespace lgh
