// surfaceTiles: the work-group tiles a frame's surfaces can cover, from the scene's bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "passes/surface_tiles.hpp"
#include "scene/scene.hpp"

namespace {

constexpr int kTile = 8;  // LGH_GROUP_2D

lgh::Bounds box(glm::vec3 low, glm::vec3 high) {
  lgh::Bounds bounds;
  bounds.extend(low);
  bounds.extend(high);
  return bounds;
}

glm::mat4 cameraAt(glm::vec3 eye, float aspect) {
  return glm::perspective(glm::radians(45.0F), aspect, 0.1F, 100.0F) *
         glm::lookAt(eye, glm::vec3(0.0F), glm::vec3(0.0F, 1.0F, 0.0F));
}

bool inside(const lgh::FrameTiles& tiles, glm::ivec2 pixel) {
  const glm::ivec2 tile = pixel / kTile;
  return tile.x >= tiles.first.x && tile.x < tiles.first.x + tiles.count.x &&
         tile.y >= tiles.first.y && tile.y < tiles.first.y + tiles.count.y;
}

// Every pixel that a point of the box projects to, or lies within `margin` pixels of, is in one
// of the tiles; and a box that fills a small part of the frame leaves most tiles out.
TEST(SurfaceTiles, HoldEveryPixelTheBoxProjectsToAndNoMore) {
  const int width = 197;
  const int height = 131;
  const lgh::Bounds bounds = box(glm::vec3(-0.3F, -0.2F, -0.4F), glm::vec3(0.5F, 0.1F, 0.2F));
  const glm::mat4 viewProjection = cameraAt(glm::vec3(2.0F, 1.5F, 4.0F), float(width) / height);
  const float margin = 6.0F;
  const lgh::FrameTiles tiles = lgh::surfaceTiles(bounds, viewProjection, width, height, margin);
  ASSERT_FALSE(tiles.empty());
  const lgh::FrameTiles all = lgh::allTiles(width, height);
  EXPECT_EQ(all.count, glm::ivec2(25, 17));
  EXPECT_LT(tiles.count.x * tiles.count.y, all.count.x * all.count.y / 2);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0F, 1.0F);
  for (int i = 0; i < 5000; ++i) {
    const glm::vec3 point =
        glm::mix(bounds.min, bounds.max, glm::vec3(unit(random), unit(random), unit(random)));
    const glm::vec4 clip = viewProjection * glm::vec4(point, 1.0F);
    const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5F + 0.5F) * glm::vec2(width, height);
    for (const glm::vec2 offset : {glm::vec2(-margin, -margin), glm::vec2(margin, margin),
                                   glm::vec2(-margin, margin), glm::vec2(margin, -margin)}) {
      const glm::ivec2 covered = glm::ivec2(glm::floor(pixel + offset));
      if (covered.x < 0 || covered.y < 0 || covered.x >= width || covered.y >= height) continue;
      EXPECT_TRUE(inside(tiles, covered)) << covered.x << ", " << covered.y;
    }
  }
}

TEST(SurfaceTiles, TheMarginWidensThemByHalfAPointSize) {
  const lgh::Bounds point = box(glm::vec3(0.0F), glm::vec3(0.0F));
  const glm::mat4 viewProjection = cameraAt(glm::vec3(0.0F, 0.0F, 3.0F), 1.0F);
  const lgh::FrameTiles narrow = lgh::surfaceTiles(point, viewProjection, 256, 256, 0.0F);
  const lgh::FrameTiles wide = lgh::surfaceTiles(point, viewProjection, 256, 256, 40.0F);
  EXPECT_EQ(narrow.count, glm::ivec2(2, 2));  // the centre's pixel, two pixels either way
  EXPECT_EQ(wide.first, glm::ivec2((128 - 42) / kTile));
  EXPECT_EQ(wide.first + wide.count, glm::ivec2((128 + 42 - 1) / kTile + 1));
}

TEST(SurfaceTiles, EveryTileWhenTheBoxReachesBehindTheCamera) {
  const glm::mat4 viewProjection = cameraAt(glm::vec3(0.0F, 0.0F, 1.0F), 1.0F);
  const lgh::Bounds around = box(glm::vec3(-0.5F), glm::vec3(0.5F, 0.5F, 2.0F));
  const lgh::FrameTiles tiles = lgh::surfaceTiles(around, viewProjection, 64, 48, 0.0F);
  EXPECT_EQ(tiles.first, glm::ivec2(0));
  EXPECT_EQ(tiles.count, glm::ivec2(8, 6));
}

TEST(SurfaceTiles, NoneForAnEmptyBoxOrOneOffScreenAndEveryTileForOneNotFinite) {
  const glm::mat4 viewProjection = cameraAt(glm::vec3(0.0F, 0.0F, 3.0F), 1.0F);
  EXPECT_TRUE(lgh::surfaceTiles(lgh::Bounds{}, viewProjection, 64, 64, 4.0F).empty());
  const lgh::Bounds aside = box(glm::vec3(40.0F, 0.0F, 0.0F), glm::vec3(41.0F, 1.0F, 1.0F));
  EXPECT_TRUE(lgh::surfaceTiles(aside, viewProjection, 64, 64, 4.0F).empty());
  const float inf = std::numeric_limits<float>::infinity();
  const lgh::Bounds infinite = box(glm::vec3(0.0F), glm::vec3(inf, 1.0F, 1.0F));
  EXPECT_EQ(lgh::surfaceTiles(infinite, viewProjection, 64, 64, 4.0F).count, glm::ivec2(8, 8));
  // Far off but finite: clamped before it becomes a pixel index.
  const lgh::Bounds far = box(glm::vec3(-1e30F, -1.0F, -1.0F), glm::vec3(1e30F, 1.0F, 1.0F));
  const lgh::FrameTiles wide = lgh::surfaceTiles(far, viewProjection, 64, 64, 0.0F);
  EXPECT_EQ(wide.count.x, 8);
}

}  // namespace
