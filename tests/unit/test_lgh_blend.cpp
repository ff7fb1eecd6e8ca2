// The LGH blending functions (renderer/testing: lgh/testing/lgh_blend.hpp, mirror of
// glsl/include/lgh_blend.glsl): a partition of unity over the levels in use at every distance,
// for many alpha, h_1, start and top levels; the shapes of docs/LGH.md and the
// paper's Fig. 2. Tolerance: 1e-5 on sums of float weights.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "lgh/testing/lgh_blend.hpp"

namespace {

constexpr float kTolerance = 1.0e-5F;

std::vector<float> distances(float rTop) {
  std::vector<float> d{0.0F};
  for (int i = 1; i <= 4000; ++i) d.push_back(2.5F * rTop * static_cast<float>(i) / 4000.0F);
  for (float x = 1.0e-6F * rTop; x < 4.0F * rTop; x *= 1.13F) d.push_back(x);
  return d;
}

TEST(LghBlend, PartitionOfUnity) {
  for (float alpha : {0.25F, 0.5F, 1.0F, 1.5F, 2.0F, 3.7F}) {
    for (float h1 : {0.01F, 0.37F, 1.0F}) {
      for (int top = 1; top <= 10; ++top) {
        for (int start = 1; start <= top; ++start) {
          for (float d : distances(lgh::lghRadius(top, alpha, h1))) {
            float sum = 0.0F;
            int nonZero = 0;
            for (int level = start; level <= top; ++level) {
              const float b = lgh::lghBlend(d, level, start, top, alpha, h1);
              ASSERT_GE(b, 0.0F);
              ASSERT_LE(b, 1.0F);
              sum += b;
              nonZero += b > 0.0F ? 1 : 0;
            }
            ASSERT_NEAR(sum, 1.0F, kTolerance) << "alpha " << alpha << " h1 " << h1 << " levels "
                                               << start << ".." << top << " d " << d;
            ASSERT_LE(nonZero, 2) << "d " << d;
          }
        }
      }
    }
  }
}

TEST(LghBlend, LowestLevelShape) {
  const float r = lgh::lghRadius(2, 1.5F, 0.2F);  // 0.6
  EXPECT_FLOAT_EQ(r, 0.6F);
  EXPECT_FLOAT_EQ(lgh::lghBlend(0.0F, 2, 2, 5, 1.5F, 0.2F), 1.0F);
  EXPECT_FLOAT_EQ(lgh::lghBlend(r, 2, 2, 5, 1.5F, 0.2F), 1.0F);
  EXPECT_NEAR(lgh::lghBlend(1.5F * r, 2, 2, 5, 1.5F, 0.2F), 0.5F, kTolerance);
  EXPECT_FLOAT_EQ(lgh::lghBlend(2.0F * r, 2, 2, 5, 1.5F, 0.2F), 0.0F);
  EXPECT_FLOAT_EQ(lgh::lghBlend(10.0F * r, 2, 2, 5, 1.5F, 0.2F), 0.0F);
}

TEST(LghBlend, MiddleLevelShape) {
  const float r = lgh::lghRadius(3, 1.0F, 1.0F);  // 4; r_(l-1) = 2
  EXPECT_FLOAT_EQ(lgh::lghBlend(0.0F, 3, 1, 5, 1.0F, 1.0F), 0.0F);
  EXPECT_FLOAT_EQ(lgh::lghBlend(0.5F * r, 3, 1, 5, 1.0F, 1.0F), 0.0F);  // minimum radius r/2
  EXPECT_NEAR(lgh::lghBlend(0.75F * r, 3, 1, 5, 1.0F, 1.0F), 0.5F, kTolerance);  // (d - r/2)/(r/2)
  EXPECT_FLOAT_EQ(lgh::lghBlend(r, 3, 1, 5, 1.0F, 1.0F), 1.0F);
  EXPECT_NEAR(lgh::lghBlend(1.5F * r, 3, 1, 5, 1.0F, 1.0F), 0.5F, kTolerance);
  EXPECT_FLOAT_EQ(lgh::lghBlend(2.0F * r, 3, 1, 5, 1.0F, 1.0F), 0.0F);
}

TEST(LghBlend, TopLevelShape) {
  const float r = lgh::lghRadius(4, 2.0F, 0.5F);  // 8
  EXPECT_FLOAT_EQ(lgh::lghBlend(0.5F * r, 4, 1, 4, 2.0F, 0.5F), 0.0F);
  EXPECT_NEAR(lgh::lghBlend(0.75F * r, 4, 1, 4, 2.0F, 0.5F), 0.5F, kTolerance);
  EXPECT_FLOAT_EQ(lgh::lghBlend(r, 4, 1, 4, 2.0F, 0.5F), 1.0F);
  EXPECT_FLOAT_EQ(lgh::lghBlend(1.0e6F * r, 4, 1, 4, 2.0F, 0.5F), 1.0F);
}

TEST(LghBlend, SingleLevelIsOneEverywhere) {
  for (float d : {0.0F, 0.1F, 5.0F, 1.0e9F}) {
    EXPECT_FLOAT_EQ(lgh::lghBlend(d, 3, 3, 3, 1.0F, 1.0F), 1.0F);
  }
}

TEST(LghBlend, ZeroOutsideLevelsAndInfluenceRadius) {
  EXPECT_EQ(lgh::lghBlend(1.0F, 1, 2, 5, 1.0F, 1.0F), 0.0F);  // below the start level
  EXPECT_EQ(lgh::lghBlend(1.0F, 6, 2, 5, 1.0F, 1.0F), 0.0F);  // above the top
  for (int level = 1; level < 6; ++level) {
    const float radius = lgh::lghInfluenceRadius(level, 6, 1.3F, 0.1F);
    EXPECT_EQ(lgh::lghBlend(radius, level, 1, 6, 1.3F, 0.1F), 0.0F);
    EXPECT_EQ(lgh::lghBlend(radius * 1.01F, level, 1, 6, 1.3F, 0.1F), 0.0F);
    EXPECT_GT(lgh::lghBlend(radius * 0.99F, level, 1, 6, 1.3F, 0.1F), 0.0F);
  }
}

}  // namespace
