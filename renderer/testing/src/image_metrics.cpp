#include "lgh/testing/image_metrics.hpp"

#include <cmath>
#include <limits>

#include "lgh/error.hpp"

namespace lgh {

ImageError compareToReference(const FloatImage& image, const FloatImage& reference) {
  if (image.width != reference.width || image.height != reference.height) {
    throw Error(ErrorCode::Invalid, "images differ in size", "reference");
  }
  double squaredError = 0.0;
  double squaredReference = 0.0;
  double peak = 0.0;
  ImageError error;
  const size_t pixels = static_cast<size_t>(image.width) * image.height;
  for (size_t p = 0; p < pixels; ++p) {
    const float* a = &image.rgba[p * 4];
    const float* r = &reference.rgba[p * 4];
    if (r[3] <= 0.0F) continue;
    ++error.pixels;
    for (int c = 0; c < 3; ++c) {
      const double difference = static_cast<double>(a[c]) - r[c];
      squaredError += difference * difference;
      squaredReference += static_cast<double>(r[c]) * r[c];
      peak = std::max(peak, static_cast<double>(r[c]));
    }
  }
  if (error.pixels == 0) return error;
  const double mse = squaredError / static_cast<double>(error.pixels * 3);
  error.rmse = std::sqrt(mse);
  error.relativeRmse = squaredReference > 0.0 ? std::sqrt(squaredError / squaredReference) : 0.0;
  error.psnr = mse > 0.0 && peak > 0.0 ? 10.0 * std::log10(peak * peak / mse)
                                       : std::numeric_limits<double>::infinity();
  return error;
}

}  // namespace lgh
