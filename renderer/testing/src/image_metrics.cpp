#include "lgh/testing/image_metrics.hpp"

#include <cmath>
#include <limits>
#include <string>

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

namespace {

double luminance(const float* rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

// The relative RMSE, PSNR and bias over the pixels `take` accepts.
template <typename Take>
ImageError errorOver(const FloatImage& image, const FloatImage& reference, Take&& take,
                     double& bias) {
  double squaredError = 0.0;
  double squaredReference = 0.0;
  double peak = 0.0;
  double sumImage = 0.0;
  double sumReference = 0.0;
  ImageError error;
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  for (std::size_t p = 0; p < pixels; ++p) {
    const float* a = &image.rgba[p * 4];
    const float* r = &reference.rgba[p * 4];
    if (r[3] <= 0.0F || !take(p)) continue;
    ++error.pixels;
    sumImage += luminance(a);
    sumReference += luminance(r);
    for (int c = 0; c < 3; ++c) {
      const double difference = static_cast<double>(a[c]) - r[c];
      squaredError += difference * difference;
      squaredReference += static_cast<double>(r[c]) * r[c];
      peak = std::max(peak, static_cast<double>(r[c]));
    }
  }
  bias = sumReference > 0.0 ? sumImage / sumReference - 1.0 : 0.0;
  if (error.pixels == 0) return error;
  const double mse = squaredError / static_cast<double>(error.pixels * 3);
  error.rmse = std::sqrt(mse);
  error.relativeRmse = squaredReference > 0.0 ? std::sqrt(squaredError / squaredReference) : 0.0;
  error.psnr = mse > 0.0 && peak > 0.0 ? 10.0 * std::log10(peak * peak / mse)
                                       : std::numeric_limits<double>::infinity();
  return error;
}

}  // namespace

bool isGlossyPixel(const glm::vec2& metallicRoughness) {
  return metallicRoughness.x > 0.5F || metallicRoughness.y < 0.5F;
}

MaterialErrors compareByMaterial(const FloatImage& image, const FloatImage& reference,
                                 const std::vector<glm::vec2>& metallicRoughness) {
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  if (image.width != reference.width || image.height != reference.height ||
      metallicRoughness.size() != pixels) {
    throw Error(ErrorCode::Invalid, "images and material classes differ in size", "reference");
  }
  MaterialErrors errors;
  errors.all = errorOver(
      image, reference, [](std::size_t) { return true; }, errors.bias);
  errors.diffuse = errorOver(
      image, reference, [&](std::size_t p) { return !isGlossyPixel(metallicRoughness[p]); },
      errors.diffuseBias);
  errors.glossy = errorOver(
      image, reference, [&](std::size_t p) { return isGlossyPixel(metallicRoughness[p]); },
      errors.glossyBias);
  errors.glossyFraction = errors.all.pixels > 0 ? static_cast<double>(errors.glossy.pixels) /
                                                      static_cast<double>(errors.all.pixels)
                                                : 0.0;
  return errors;
}

FloatImage multiplied(const FloatImage& image, const FloatImage& factor) {
  if (image.width != factor.width || image.height != factor.height) {
    throw Error(ErrorCode::Invalid, "images differ in size", "factor");
  }
  FloatImage product = image;
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  for (std::size_t p = 0; p < pixels; ++p) {
    for (int c = 0; c < 3; ++c) product.rgba[p * 4 + c] *= factor.rgba[p * 4];
  }
  return product;
}

}  // namespace lgh
