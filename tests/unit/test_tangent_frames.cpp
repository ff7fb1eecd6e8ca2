// Tangent frames on the assimp-testmodels glTF assets (Debian's assimp-testmodels): MikkTSpace
// (scene/mikktspace.hpp) generated for every textured triangle primitive, as normal, bump,
// parallax and relief mapping read them. Per vertex: finite, unit, orthogonal to the normal, w
// = +-1. Per triangle with UV and surface area: t follows the direction of increasing u and
// cross(n, t) w the direction of decreasing v (glTF's UV origin is the image's top-left), at
// every corner. AnimatedMorphCube has no texture coordinates at all: its frames must still be
// valid (what a bump or relief map over it would read).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include "scene/gltf/gltf_loader.hpp"
#include "scene/mikktspace.hpp"
#include "test_support.hpp"

namespace {

struct FrameStats {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  std::size_t followingU = 0;  // corners whose t has a positive component along dP/du
  std::size_t followingV = 0;  // corners whose bitangent has a positive component along -dP/dv
  std::size_t corners = 0;
};

void checkVertices(const lgh::Primitive& primitive, const std::string& where) {
  for (const lgh::Vertex& v : primitive.vertices) {
    const glm::vec3 t(v.tangent);
    ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) << where;
    EXPECT_NEAR(glm::length(t), 1.0F, 1e-4F) << where;
    EXPECT_NEAR(glm::dot(t, v.normal), 0.0F, 2e-3F) << where;
    EXPECT_EQ(std::abs(v.tangent.w), 1.0F) << where;
  }
}

// dP/du and dP/dv of a triangle, from the lecture's "UVW to object space" system.
bool triangleAxes(const lgh::Vertex& a, const lgh::Vertex& b, const lgh::Vertex& c, glm::vec3& dPdu,
                  glm::vec3& dPdv) {
  const glm::vec3 e1 = b.position - a.position;
  const glm::vec3 e2 = c.position - a.position;
  const glm::vec2 d1 = b.uv0 - a.uv0;
  const glm::vec2 d2 = c.uv0 - a.uv0;
  const float det = d1.x * d2.y - d2.x * d1.y;
  if (std::abs(det) < 1e-10F || glm::length(glm::cross(e1, e2)) < 1e-10F) return false;
  dPdu = (e1 * d2.y - e2 * d1.y) / det;
  dPdv = (e2 * d1.x - e1 * d2.x) / det;
  return true;
}

FrameStats measure(const lgh::Primitive& primitive) {
  FrameStats stats;
  stats.vertices = primitive.vertices.size();
  for (std::size_t i = 0; i + 2 < primitive.indices.size(); i += 3) {
    const lgh::Vertex* corner[3] = {&primitive.vertices[primitive.indices[i]],
                                    &primitive.vertices[primitive.indices[i + 1]],
                                    &primitive.vertices[primitive.indices[i + 2]]};
    glm::vec3 dPdu;
    glm::vec3 dPdv;
    if (!triangleAxes(*corner[0], *corner[1], *corner[2], dPdu, dPdv)) continue;
    ++stats.triangles;
    for (const lgh::Vertex* v : corner) {
      const glm::vec3 t(v->tangent);
      const glm::vec3 bitangent = glm::cross(v->normal, t) * v->tangent.w;
      ++stats.corners;
      if (glm::dot(t, dPdu) > 0.0F) ++stats.followingU;
      if (glm::dot(bitangent, -dPdv) > 0.0F) ++stats.followingV;
    }
  }
  return stats;
}

TEST(TangentFrames, MikkTSpaceOnTheTexturedAssimpAssets) {
  const std::vector<std::string> assets = {
      "BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
      "BoxTexcoords-glTF/boxTexcoords.gltf", "ClearCoat-glTF/ClearCoatTest.gltf",
      "textureTransform/TextureTransformTest.gltf"};
  std::size_t checkedPrimitives = 0;
  for (const std::string& asset : assets) {
    SCOPED_TRACE(asset);
    const lgh::Scene scene = lgh::loadGltfFile(lgh::test::assimpGltfDir(), asset);
    FrameStats total;
    for (const lgh::Mesh& mesh : scene.meshes) {
      for (lgh::Primitive primitive : mesh.primitives) {
        lgh::generateMikkTSpaceTangents(primitive, 0);
        checkVertices(primitive, asset + " " + mesh.name);
        const FrameStats stats = measure(primitive);
        if (stats.triangles == 0) continue;  // no UV area: nothing to follow
        ++checkedPrimitives;
        total.vertices += stats.vertices;
        total.triangles += stats.triangles;
        total.corners += stats.corners;
        total.followingU += stats.followingU;
        total.followingV += stats.followingV;
      }
    }
    ASSERT_GT(total.triangles, 0U);
    std::cout << fmt::format(
        "{}: {} vertices, {} triangles; t along +u at {}/{} corners, "
        "bitangent along -v at {}/{}\n",
        asset, total.vertices, total.triangles, total.followingU, total.corners, total.followingV,
        total.corners);
    // Every corner: the frame averages triangles of one UV orientation around a vertex, and these
    // assets have no UV shear large enough to turn an axis around.
    EXPECT_EQ(total.followingU, total.corners);
    EXPECT_EQ(total.followingV, total.corners);
  }
  EXPECT_GE(checkedPrimitives, assets.size());
}

TEST(TangentFrames, ValidWithoutTextureCoordinates) {
  const lgh::Scene scene =
      lgh::loadGltfFile(lgh::test::assimpGltfDir(),
                        "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
  std::size_t vertices = 0;
  for (const lgh::Mesh& mesh : scene.meshes) {
    for (lgh::Primitive primitive : mesh.primitives) {
      lgh::generateMikkTSpaceTangents(primitive, 0);
      checkVertices(primitive, mesh.name);
      vertices += primitive.vertices.size();
    }
  }
  EXPECT_GT(vertices, 0U);
}

}  // namespace
