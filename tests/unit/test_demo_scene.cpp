// The built-in demo scene: geometry, frames, materials and lights are what demo_scene.hpp says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene/demo_scene.hpp"

namespace {

using lgh::Scene;

class DemoScene : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { scene_ = new Scene(lgh::makeDemoScene()); }
  static void TearDownTestSuite() {
    delete scene_;
    scene_ = nullptr;
  }
  static const Scene& scene() { return *scene_; }

 private:
  static Scene* scene_;
};

Scene* DemoScene::scene_ = nullptr;

TEST_F(DemoScene, IsNamedAndHasSaneTriangleCount) {
  EXPECT_EQ(scene().name, "demo");
  const std::size_t triangles = scene().triangleCount();
  EXPECT_GT(triangles, 500U);  // the sphere alone is over a thousand
  EXPECT_LT(triangles, 20000U);
  EXPECT_TRUE(scene().warnings.empty());
}

TEST_F(DemoScene, BoundsAreTheRoom) {
  const lgh::Bounds& bounds = scene().bounds;
  ASSERT_FALSE(bounds.empty());
  const float eps = 1e-4F;
  EXPECT_NEAR(bounds.min.x, -1.0F, eps);
  EXPECT_NEAR(bounds.min.y, 0.0F, eps);
  EXPECT_NEAR(bounds.min.z, -1.0F, eps);
  EXPECT_NEAR(bounds.max.x, 1.0F, eps);
  EXPECT_NEAR(bounds.max.y, 2.0F, eps);
  EXPECT_NEAR(bounds.max.z, 1.0F, eps);
}

TEST_F(DemoScene, InstancesAndIndicesAreValid) {
  for (const lgh::MeshInstance& instance : scene().instances) {
    ASSERT_GE(instance.mesh, 0);
    ASSERT_LT(static_cast<std::size_t>(instance.mesh), scene().meshes.size());
  }
  for (const lgh::Mesh& mesh : scene().meshes) {
    for (const lgh::Primitive& primitive : mesh.primitives) {
      ASSERT_EQ(primitive.indices.size() % 3, 0U) << mesh.name;
      for (std::uint32_t index : primitive.indices) ASSERT_LT(index, primitive.vertices.size());
      ASSERT_GE(primitive.material, 0);
      ASSERT_LT(static_cast<std::size_t>(primitive.material), scene().materials.size());
    }
  }
}

TEST_F(DemoScene, FramesAreUnitOrthogonalAndRightHanded) {
  for (const lgh::Mesh& mesh : scene().meshes) {
    for (const lgh::Primitive& primitive : mesh.primitives) {
      for (const lgh::Vertex& v : primitive.vertices) {
        EXPECT_NEAR(glm::length(v.normal), 1.0F, 1e-4F) << mesh.name;
        EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0F, 1e-4F) << mesh.name;
        EXPECT_NEAR(glm::dot(v.normal, glm::vec3(v.tangent)), 0.0F, 1e-4F) << mesh.name;
        EXPECT_EQ(v.tangent.w, 1.0F) << mesh.name;
      }
    }
  }
}

// Counter-clockwise winding agrees with the vertex normals, so back-face culling keeps the faces
// the normals point out of (room walls: into the room; boxes and sphere: outwards).
TEST_F(DemoScene, WindingMatchesNormals) {
  for (const lgh::Mesh& mesh : scene().meshes) {
    for (const lgh::Primitive& primitive : mesh.primitives) {
      for (std::size_t i = 0; i < primitive.indices.size(); i += 3) {
        const lgh::Vertex& a = primitive.vertices[primitive.indices[i]];
        const lgh::Vertex& b = primitive.vertices[primitive.indices[i + 1]];
        const lgh::Vertex& c = primitive.vertices[primitive.indices[i + 2]];
        const glm::vec3 face = glm::cross(b.position - a.position, c.position - a.position);
        ASSERT_GT(glm::length(face), 0.0F) << mesh.name << " triangle " << i / 3;
        EXPECT_GT(glm::dot(face, a.normal + b.normal + c.normal), 0.0F)
            << mesh.name << " triangle " << i / 3;
      }
    }
  }
}

// The tangent is dP/du and the bitangent cross(n, t) * w points along decreasing v (glTF).
TEST_F(DemoScene, TangentsFollowTheUvs) {
  for (const lgh::Mesh& mesh : scene().meshes) {
    for (const lgh::Primitive& primitive : mesh.primitives) {
      for (std::size_t i = 0; i < primitive.indices.size(); i += 3) {
        const lgh::Vertex& a = primitive.vertices[primitive.indices[i]];
        const lgh::Vertex& b = primitive.vertices[primitive.indices[i + 1]];
        const lgh::Vertex& c = primitive.vertices[primitive.indices[i + 2]];
        const glm::vec3 e1 = b.position - a.position, e2 = c.position - a.position;
        const glm::vec2 d1 = b.uv0 - a.uv0, d2 = c.uv0 - a.uv0;
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (std::abs(det) < 1e-8F) continue;
        const glm::vec3 dPdu = (e1 * d2.y - e2 * d1.y) / det;
        const glm::vec3 dPdv = (e2 * d1.x - e1 * d2.x) / det;
        const glm::vec3 bitangent = glm::cross(a.normal, glm::vec3(a.tangent)) * a.tangent.w;
        EXPECT_GT(glm::dot(glm::vec3(a.tangent), dPdu), 0.0F) << mesh.name;
        EXPECT_GT(glm::dot(bitangent, -dPdv), 0.0F) << mesh.name;
      }
    }
  }
}

TEST_F(DemoScene, RoomWallsFaceInwards) {
  const lgh::Mesh& room = scene().meshes.at(0);
  ASSERT_EQ(room.name, "room");
  for (const lgh::Primitive& primitive : room.primitives) {
    for (const lgh::Vertex& v : primitive.vertices) {
      const glm::vec3 toCentre = glm::vec3(0, 1, 0) - v.position;
      EXPECT_GT(glm::dot(v.normal, toCentre), 0.0F);
    }
  }
}

TEST_F(DemoScene, MaterialsAndCheckerTexture) {
  const auto& materials = scene().materials;
  ASSERT_GE(materials.size(), 5U);
  bool metallicSphere = false;
  bool emissivePanel = false;
  for (const lgh::Material& m : materials) {
    if (m.metallicFactor == 1.0F && std::abs(m.roughnessFactor - 0.3F) < 1e-6F) {
      metallicSphere = true;
    }
    if (m.emissiveFactor.x > 0.5F) emissivePanel = true;
    // The room's dielectrics (the model row below has its own parameters).
    if (m.metallicFactor == 0.0F && m.name.rfind("model_", 0) != 0) {
      EXPECT_NEAR(m.roughnessFactor, 0.8F, 1e-6F) << m.name;
    }
  }
  EXPECT_TRUE(metallicSphere);
  EXPECT_TRUE(emissivePanel);
  ASSERT_TRUE(materials[0].baseColorTexture.valid());
  // The checker, a brick height map, its normal map, a light map and the bricks' colour, each a
  // texture by index.
  ASSERT_EQ(scene().images.size(), 5U);
  ASSERT_EQ(scene().textures.size(), 5U);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(scene().textures[static_cast<std::size_t>(i)].image, i);
  const lgh::Image8& checker = scene().images[0];
  EXPECT_EQ(checker.channels, 4);
  ASSERT_EQ(checker.pixels.size(), static_cast<std::size_t>(checker.width) * checker.height * 4);
  // 8 x 8 tiles: the first two tiles of the top row differ, the first and third match.
  const int tile = checker.width / 8;
  auto grey = [&](int x, int y) {
    return checker.pixels[(static_cast<std::size_t>(y) * checker.width + x) * 4];
  };
  EXPECT_NE(grey(tile / 2, tile / 2), grey(tile + tile / 2, tile / 2));
  EXPECT_EQ(grey(tile / 2, tile / 2), grey(2 * tile + tile / 2, tile / 2));
}

// The lecture's models side by side: six spheres on the floor in front, one model each.
TEST_F(DemoScene, RowOfIlluminationModels) {
  const std::vector<std::pair<std::string, lgh::MaterialModel>> expected = {
      {"ggx_sphere", lgh::MaterialModel::MetallicRoughness},
      {"phong_sphere", lgh::MaterialModel::Phong},
      {"blinn_phong_sphere", lgh::MaterialModel::BlinnPhong},
      {"lambert_sphere", lgh::MaterialModel::OrenNayar},
      {"oren_nayar_sphere", lgh::MaterialModel::OrenNayar},
      {"cook_torrance_sphere", lgh::MaterialModel::CookTorrance}};
  float previousX = -2.0F;
  for (const auto& [name, model] : expected) {
    SCOPED_TRACE(name);
    const auto mesh = std::find_if(scene().meshes.begin(), scene().meshes.end(),
                                   [&](const lgh::Mesh& m) { return m.name == name; });
    ASSERT_NE(mesh, scene().meshes.end());
    const int material = mesh->primitives.at(0).material;
    EXPECT_EQ(scene().materials.at(static_cast<std::size_t>(material)).model, model);
    const auto meshIndex = static_cast<int>(mesh - scene().meshes.begin());
    const auto instance =
        std::find_if(scene().instances.begin(), scene().instances.end(),
                     [&](const lgh::MeshInstance& i) { return i.mesh == meshIndex; });
    ASSERT_NE(instance, scene().instances.end());
    const float x = instance->world[3].x;
    EXPECT_GT(x, previousX);                         // left to right
    EXPECT_NEAR(instance->world[3].y, 0.1F, 1e-6F);  // resting on the floor
    previousX = x;
  }
  const auto lambert =
      std::find_if(scene().materials.begin(), scene().materials.end(),
                   [](const lgh::Material& m) { return m.name == "model_lambert"; });
  ASSERT_NE(lambert, scene().materials.end());
  EXPECT_EQ(lambert->classic.sigma, 0.0F);
}

TEST_F(DemoScene, HasPointSpotAndDirectionalLights) {
  int point = 0, spot = 0, directional = 0;
  for (const lgh::LightDesc& light : scene().lights) {
    EXPECT_GT(light.intensity, 0.0F);
    const glm::vec3 direction(light.direction[0], light.direction[1], light.direction[2]);
    EXPECT_NEAR(glm::length(direction), 1.0F, 1e-5F);
    EXPECT_EQ(light.attenuation[2], 1.0F);
    switch (light.type) {
      case lgh::LightType::Point:
        ++point;
        EXPECT_GT(light.position[1], 1.5F);  // near the ceiling
        EXPECT_LT(light.position[1], 2.0F);
        break;
      case lgh::LightType::Spot:
        ++spot;
        EXPECT_LT(light.innerConeAngle, light.outerConeAngle);
        break;
      case lgh::LightType::Directional:
        ++directional;
        EXPECT_LT(light.intensity, 1.0F);  // dim fill
        break;
    }
  }
  EXPECT_EQ(point, 1);
  EXPECT_EQ(spot, 1);
  EXPECT_EQ(directional, 1);
}

TEST_F(DemoScene, HasACameraLookingIntoTheRoom) {
  ASSERT_EQ(scene().cameras.size(), 1U);
  const lgh::SceneCamera& camera = scene().cameras[0];
  const glm::vec3 position(camera.world[3]);
  const glm::vec3 forward = -glm::vec3(camera.world[2]);
  EXPECT_GT(position.z, 1.0F);  // outside the open front
  EXPECT_GT(glm::dot(forward, glm::vec3(0, 1, 0) - position), 0.0F);
}

}  // namespace
