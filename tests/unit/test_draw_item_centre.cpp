// The world-space centre that blended surfaces are sorted by (GpuScene::centreOf), computed from
// the item's primitive when a frame asks for it, without GL: the centre of the primitive's bounds
// placed by the instance's transform; the instance's origin when there is nothing to bound.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/gpu_scene.hpp"
#include "scene/scene.hpp"

namespace {

using lgh::GpuScene;

lgh::Primitive primitiveOver(const std::vector<glm::vec3>& positions) {
  lgh::Primitive primitive;
  for (const glm::vec3& position : positions) primitive.vertices.push_back({.position = position});
  return primitive;
}

TEST(DrawItemCentre, TheBoundsCentrePlacedByTheInstance) {
  const lgh::Primitive primitive = primitiveOver({{0, 0, 0}, {2, 1, 0}, {1, 2, 4}, {0.5F, 0, 1}});
  GpuScene::DrawItem item{};
  item.primitive = &primitive;
  item.world = glm::mat4(1.0F);
  EXPECT_EQ(GpuScene::centreOf(item), glm::vec3(1, 1, 2));
  item.world = glm::scale(glm::translate(glm::mat4(1.0F), {5, 0, -3}), {2, 2, 2});
  EXPECT_EQ(GpuScene::centreOf(item), glm::vec3(7, 2, 1));
}

TEST(DrawItemCentre, NothingToBoundIsTheInstancesOrigin) {
  const lgh::Primitive empty;
  GpuScene::DrawItem item{};
  item.world = glm::translate(glm::mat4(1.0F), {1, 2, 3});
  EXPECT_EQ(GpuScene::centreOf(item), glm::vec3(1, 2, 3)) << "no primitive";
  item.primitive = &empty;
  EXPECT_EQ(GpuScene::centreOf(item), glm::vec3(1, 2, 3)) << "a primitive without vertices";
}

}  // namespace
