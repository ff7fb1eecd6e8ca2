// Error metrics between a rendered image and a reference (e.g. the brute-force many-light image).
#pragma once

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

}  // namespace lgh
