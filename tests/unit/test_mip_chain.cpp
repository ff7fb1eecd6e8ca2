// The mip chains the CPU builds where the driver's glGenerateMipmap is slow (llvmpipe;
// scene/blit_mip_chain.hpp), pure CPU:
//  - even sides: each texel the mean of its 2x2 block, rounded for data as llvmpipe's blit to half
//    size rounds it (a rounded mean of each row's pair, then of the rows': the same bytes as its
//    glGenerateMipmap, checked against it in tests/integration/test_material_techniques.cpp), and
//    to the nearest code in linear light for sRGB colour (alpha: the mean rounded half up);
//  - odd sides: bilinear samples at the texels' centres, as a GPU's blit to half size takes them,
//    so that a level does not drift against the one above it;
//  - every sRGB code survives the average of itself (the encoder inverts the decoding exactly);
//  - levels halve down to 1 x 1.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "lgh/image.hpp"
#include "scene/blit_mip_chain.hpp"

namespace {

lgh::Image8 image(int width, int height, const std::vector<std::uint8_t>& grey) {
  lgh::Image8 result;
  result.width = width;
  result.height = height;
  result.channels = 4;
  for (const std::uint8_t value : grey) {
    result.pixels.insert(result.pixels.end(), {value, value, value, 255});
  }
  return result;
}

TEST(MipChain, EvenSidesTakeTheRoundedMeanOfEachRowsPairThenOfTheRows) {
  const lgh::Image8 source = image(4, 2, {0, 1, 10, 20, 2, 3, 30, 41});
  const std::vector<lgh::Image8> chain = lgh::buildBlitMipChain(source, false);
  ASSERT_EQ(chain.size(), 2U);
  ASSERT_EQ(chain[0].width, 2);
  ASSERT_EQ(chain[0].height, 1);
  EXPECT_EQ(chain[0].pixels[0], 2);   // (0 + 1) / 2 -> 1, (2 + 3) / 2 -> 3, (1 + 3) / 2 = 2
  EXPECT_EQ(chain[0].pixels[4], 26);  // 15 and 35.5 -> 36: 25.5 -> 26 (the exact mean 25.25)
  EXPECT_EQ(chain[0].pixels[3], 255);
  EXPECT_EQ(chain[1].pixels[0], 14);  // a 1-high level repeats its row: (2 + 26) / 2 = 14
}

TEST(MipChain, SrgbColourIsAveragedInLinearLight) {
  const lgh::Image8 source = image(2, 1, {0, 255});
  EXPECT_EQ(lgh::buildBlitMipChain(source, false)[0].pixels[0], 128);
  // Linear 0.5 is sRGB 0.7354 of 255: code 188 (a mean of the codes would give 128).
  const lgh::Image8 colour = lgh::buildBlitMipChain(source, true)[0];
  EXPECT_EQ(colour.pixels[0], 188);
  EXPECT_EQ(colour.pixels[3], 255) << "alpha is data";
}

TEST(MipChain, EveryCodeSurvivesTheMeanOfItself) {
  for (int code = 0; code < 256; ++code) {
    const auto value = static_cast<std::uint8_t>(code);
    for (const bool srgb : {false, true}) {
      const std::vector<lgh::Image8> chain =
          lgh::buildBlitMipChain(image(2, 2, {value, value, value, value}), srgb);
      ASSERT_EQ(chain.size(), 1U);
      EXPECT_EQ(chain[0].pixels[0], value) << code << (srgb ? " sRGB" : "");
    }
  }
}

TEST(MipChain, OddSidesAreSampledAtTheTexelsCentres) {
  // 3 x 3 to 1 x 1: the one texel's centre is the middle texel's; a 2x2 box from the corner (what
  // a halving that drops the last row and column takes) would mix in three others.
  std::vector<std::uint8_t> grey(9, 0);
  grey[4] = 200;
  const std::vector<lgh::Image8> chain = lgh::buildBlitMipChain(image(3, 3, grey), false);
  ASSERT_EQ(chain.size(), 1U);
  EXPECT_EQ(chain[0].pixels[0], 200);
  // 5 wide to 2: centres at 0.75 and 3.25 of the source's texels.
  const lgh::Image8 row = lgh::buildBlitMipChain(image(5, 1, {0, 100, 0, 0, 200}), false)[0];
  ASSERT_EQ(row.width, 2);
  EXPECT_EQ(row.pixels[0], 75);  // 0 + 0.75 x (100 - 0)
  EXPECT_EQ(row.pixels[4], 50);  // 0 + 0.25 x (200 - 0)
}

TEST(MipChain, LevelsHalveDownToOneTexel) {
  const std::vector<lgh::Image8> chain =
      lgh::buildBlitMipChain(image(5, 3, std::vector<std::uint8_t>(15, 7)), true);
  ASSERT_EQ(chain.size(), 2U);
  EXPECT_EQ(chain[0].width, 2);
  EXPECT_EQ(chain[0].height, 1);
  EXPECT_EQ(chain[1].width, 1);
  EXPECT_EQ(chain[1].height, 1);
  for (const lgh::Image8& level : chain) {
    EXPECT_EQ(level.pixels.size(), static_cast<std::size_t>(level.width) * level.height * 4);
    EXPECT_EQ(level.pixels[0], 7);
  }
}

}  // namespace
