#include <gtest/gtest.h>

#include <cmath>

#include "lgh/error.hpp"
#include "lgh/testing/image_metrics.hpp"

namespace {

lgh::FloatImage constantImage(int width, int height, float value, float alpha = 1.0F) {
  lgh::FloatImage image;
  image.width = width;
  image.height = height;
  image.rgba.assign(static_cast<size_t>(width) * height * 4, value);
  for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = alpha;
  return image;
}

TEST(ImageMetrics, IdenticalImagesHaveZeroErrorAndInfinitePsnr) {
  auto image = constantImage(4, 3, 0.5F);
  auto error = lgh::compareToReference(image, image);
  EXPECT_EQ(error.relativeRmse, 0.0);
  EXPECT_TRUE(std::isinf(error.psnr));
  EXPECT_EQ(error.pixels, 12U);
}

TEST(ImageMetrics, ScaledImageHasRelativeRmseOfTheScale) {
  auto reference = constantImage(8, 8, 2.0F);
  auto image = constantImage(8, 8, 2.2F);
  auto error = lgh::compareToReference(image, reference);
  EXPECT_NEAR(error.relativeRmse, 0.1, 1e-6);
  EXPECT_NEAR(error.rmse, 0.2, 1e-6);
  // peak 2, mse 0.04: 10 log10(4 / 0.04) = 20 dB
  EXPECT_NEAR(error.psnr, 20.0, 1e-4);
}

TEST(ImageMetrics, UncoveredReferencePixelsAreIgnored) {
  auto reference = constantImage(2, 2, 1.0F, 0.0F);
  reference.rgba[3] = 1.0F;  // only pixel 0 covered
  auto image = constantImage(2, 2, 5.0F);
  image.rgba[0] = image.rgba[1] = image.rgba[2] = 1.0F;
  auto error = lgh::compareToReference(image, reference);
  EXPECT_EQ(error.pixels, 1U);
  EXPECT_EQ(error.relativeRmse, 0.0);
}

TEST(ImageMetrics, SizeMismatchIsAnError) {
  EXPECT_THROW(lgh::compareToReference(constantImage(2, 2, 1), constantImage(3, 2, 1)), lgh::Error);
}

}  // namespace
