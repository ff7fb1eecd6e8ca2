// The C++ mirror of the shadow-sample reservoir (renderer/testing: lgh/testing/reservoir.hpp, the
// same code as glsl/include/reservoir.glsl): selection frequencies match f_i / sum f by a
// chi-square test (fixed seeds, p-value threshold 1e-3), whatever the order the lights stream in;
// the k samples of a pixel are independent; the jitter has the light's variance; the weights make
// the ratio estimator's mean the f-weighted visibility. tests/integration/test_lgh_lighting.cpp
// runs the GLSL on the GPU against this mirror.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include "lgh/testing/reservoir.hpp"

namespace {

namespace rs = lgh::reservoir;

constexpr double kMinPValue = 1e-3;
constexpr std::uint32_t kFrameSeed = 12345;

// Upper regularized incomplete gamma Q(a, x) (Numerical Recipes: series below a + 1, continued
// fraction above): the chi-square p-value is Q(dof / 2, statistic / 2).
double upperGammaQ(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double logPrefix = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a;
    double sum = term;
    for (int n = 1; n < 10000 && std::fabs(term) > std::fabs(sum) * 1e-15; ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return 1.0 - sum * std::exp(logPrefix);
  }
  double b = x + 1.0 - a;
  double c = 1.0 / 1e-300;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    d = std::fabs(d) < 1e-300 ? 1e-300 : d;
    c = b + an / c;
    c = std::fabs(c) < 1e-300 ? 1e-300 : c;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < 1e-15) break;
  }
  return std::exp(logPrefix) * h;
}

// Pearson's chi-square p-value of observed counts against expected probabilities (> 0).
double chiSquarePValue(const std::vector<double>& observed,
                       const std::vector<double>& probability) {
  const double total = std::accumulate(observed.begin(), observed.end(), 0.0);
  double statistic = 0.0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    const double expected = total * probability[i];
    statistic += (observed[i] - expected) * (observed[i] - expected) / expected;
  }
  return upperGammaQ(0.5 * static_cast<double>(observed.size() - 1), 0.5 * statistic);
}

const std::vector<float> kWeights{0.5F, 1.0F, 2.0F, 3.0F, 0.0F, 4.0F, 8.0F, 0.25F, 1.5F, 6.0F};

std::vector<std::uint32_t> streamOrder(bool reversed) {
  std::vector<std::uint32_t> order(kWeights.size());
  std::iota(order.begin(), order.end(), 0U);
  if (reversed) std::reverse(order.begin(), order.end());
  return order;
}

rs::Reservoir streamPixel(std::uint32_t pixel, const std::vector<std::uint32_t>& order, int k) {
  rs::Reservoir reservoir;
  const std::uint32_t seed = rs::pixelSeed(kFrameSeed, pixel);
  for (std::uint32_t light : order) reservoir.add(seed, light, kWeights[light], k);
  return reservoir;
}

// Expected probabilities and observed counts over the lights with f > 0.
struct Frequencies {
  std::vector<double> observed;
  std::vector<double> probability;
};

Frequencies selectionFrequencies(int pixels, int k, bool reversed) {
  const double sum = std::accumulate(kWeights.begin(), kWeights.end(), 0.0);
  std::vector<double> counts(kWeights.size(), 0.0);
  const auto order = streamOrder(reversed);
  for (int p = 0; p < pixels; ++p) {
    const rs::Reservoir reservoir = streamPixel(static_cast<std::uint32_t>(p), order, k);
    for (int s = 0; s < k; ++s) counts[reservoir.light[static_cast<std::size_t>(s)]] += 1.0;
  }
  Frequencies result;
  for (std::size_t i = 0; i < kWeights.size(); ++i) {
    if (kWeights[i] > 0.0F) {
      result.observed.push_back(counts[i]);
      result.probability.push_back(kWeights[i] / sum);
    } else {
      EXPECT_EQ(counts[i], 0.0) << "a light with f = 0 was chosen";
    }
  }
  return result;
}

TEST(Reservoir, ChiSquareTestOfTheTestItself) {
  EXPECT_NEAR(upperGammaQ(1.0, 2.0), std::exp(-2.0), 1e-12);  // dof 2: p = exp(-x/2)
  EXPECT_NEAR(upperGammaQ(4.5, 0.5 * 16.919), 0.05, 1e-4);    // dof 9, 95% quantile
  EXPECT_NEAR(upperGammaQ(4.5, 0.5 * 27.877), 0.001, 2e-5);   // dof 9, 99.9% quantile
}

TEST(Reservoir, FirstLightIsAlwaysChosen) {
  for (std::uint32_t pixel = 0; pixel < 100; ++pixel) {
    rs::Reservoir reservoir;
    reservoir.add(rs::pixelSeed(kFrameSeed, pixel), 7, 0.3F, 8);
    for (int s = 0; s < 8; ++s) {
      EXPECT_EQ(reservoir.light[static_cast<std::size_t>(s)], 7U);
      EXPECT_EQ(reservoir.weight[static_cast<std::size_t>(s)], 0.3F);
    }
  }
}

TEST(Reservoir, ZeroWeightsNeitherCountNorReplace) {
  rs::Reservoir reservoir;
  const std::uint32_t seed = rs::pixelSeed(kFrameSeed, 3);
  reservoir.add(seed, 1, 2.0F, 4);
  reservoir.add(seed, 2, 0.0F, 4);
  EXPECT_EQ(reservoir.runningSum, 2.0F);
  for (int s = 0; s < 4; ++s) EXPECT_EQ(reservoir.light[static_cast<std::size_t>(s)], 1U);
}

TEST(Reservoir, FrequenciesMatchWeightsByChiSquare) {
  const Frequencies f = selectionFrequencies(50000, 4, false);
  const double p = chiSquarePValue(f.observed, f.probability);
  std::cout << "[ reservoir ] CPU chi-square p-value (forward order, 200000 draws): " << p << '\n';
  EXPECT_GT(p, kMinPValue);
}

TEST(Reservoir, FrequenciesDoNotDependOnStreamOrder) {
  const Frequencies f = selectionFrequencies(50000, 4, true);
  const double p = chiSquarePValue(f.observed, f.probability);
  std::cout << "[ reservoir ] CPU chi-square p-value (reverse order): " << p << '\n';
  EXPECT_GT(p, kMinPValue);
}

TEST(Reservoir, SamplesOfAPixelAreIndependent) {
  // Joint counts of (sample 0, sample 1) against p_i p_j.
  const double sum = std::accumulate(kWeights.begin(), kWeights.end(), 0.0);
  std::vector<std::size_t> lit;
  for (std::size_t i = 0; i < kWeights.size(); ++i) {
    if (kWeights[i] > 0.0F) lit.push_back(i);
  }
  std::vector<double> counts(kWeights.size() * kWeights.size(), 0.0);
  const auto order = streamOrder(false);
  for (std::uint32_t pixel = 0; pixel < 200000; ++pixel) {
    const rs::Reservoir reservoir = streamPixel(pixel, order, 2);
    counts[reservoir.light[0] * kWeights.size() + reservoir.light[1]] += 1.0;
  }
  std::vector<double> observed;
  std::vector<double> probability;
  for (std::size_t i : lit) {
    for (std::size_t j : lit) {
      observed.push_back(counts[i * kWeights.size() + j]);
      probability.push_back(kWeights[i] / sum * kWeights[j] / sum);
    }
  }
  const double p = chiSquarePValue(observed, probability);
  std::cout << "[ reservoir ] CPU chi-square p-value of sample pairs: " << p << '\n';
  EXPECT_GT(p, kMinPValue);
}

TEST(Reservoir, JitterHasTheLightsVariance) {
  const glm::vec3 center(1.0F, -2.0F, 0.5F);
  const glm::vec3 variance(0.04F, 0.0F, 0.25F);
  glm::dvec3 mean(0.0);
  glm::dvec3 second(0.0);
  constexpr int kCount = 100000;
  for (int i = 0; i < kCount; ++i) {
    const std::uint32_t seed =
        rs::lightSeed(rs::pixelSeed(kFrameSeed, static_cast<std::uint32_t>(i)), 9);
    const glm::vec3 p = rs::jitter(center, variance, seed, static_cast<std::uint32_t>(i % 8));
    const glm::vec3 offset = p - center;
    ASSERT_LE(std::fabs(offset.x), std::sqrt(3.0F * variance.x) * 1.0001F);
    ASSERT_EQ(offset.y, 0.0F);
    mean += glm::dvec3(offset);
    second += glm::dvec3(offset) * glm::dvec3(offset);
  }
  mean /= kCount;
  second /= kCount;
  EXPECT_NEAR(mean.x, 0.0, 0.002);
  EXPECT_NEAR(mean.z, 0.0, 0.005);
  EXPECT_NEAR(second.x, 0.04, 0.04 * 0.02);
  EXPECT_NEAR(second.z, 0.25, 0.25 * 0.02);
}

TEST(Reservoir, RatioEstimatorMeanIsTheWeightedVisibility) {
  // Visibility V_i per light; per pixel the estimate sum_s f_s w_s V_s / F = mean of V_s.
  const std::vector<int> visible{1, 0, 1, 1, 0, 0, 1, 0, 1, 0};
  double expected = 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < kWeights.size(); ++i) {
    expected += kWeights[i] * visible[i];
    sum += kWeights[i];
  }
  expected /= sum;
  constexpr int kSamples = 4;
  constexpr int kPixels = 40000;
  double total = 0.0;
  const auto order = streamOrder(false);
  for (int pixel = 0; pixel < kPixels; ++pixel) {
    const rs::Reservoir r = streamPixel(static_cast<std::uint32_t>(pixel), order, kSamples);
    double shadowed = 0.0;
    for (int s = 0; s < kSamples; ++s) {
      const auto slot = static_cast<std::size_t>(s);
      const float w = rs::sampleWeight(r.runningSum, r.weight[slot], kSamples);
      shadowed += r.weight[slot] * w * visible[r.light[slot]];
    }
    total += shadowed / r.runningSum;
  }
  const double mean = total / kPixels;
  // Standard error of a mean of 4 Bernoulli(expected) per pixel.
  const double sigma = std::sqrt(expected * (1.0 - expected) / (kSamples * kPixels));
  EXPECT_NEAR(mean, expected, 4.0 * sigma);
}

TEST(Reservoir, HashIsPinned) {
  // The GPU test compares choices bit for bit with this mirror; pin the hash too.
  EXPECT_EQ(rs::hash(0U), 129708002U);
  EXPECT_EQ(rs::unit(0xffffffffU), 16777215.0F / 16777216.0F);
}

}  // namespace
