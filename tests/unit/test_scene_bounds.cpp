// Scene::computeBounds, which automatic framing and the LGH grid read.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace {

// Scene bounds are exact: every vertex an index refers to, in every instance's placement; a
// vertex no index refers to, or an index past the vertices, counts for nothing.
TEST(SceneBounds, EveryReferencedVertexOfEveryInstanceAndNothingElse) {
  lgh::Scene scene;
  lgh::Primitive triangle;
  for (const glm::vec3& position : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 2, 0),
                                    glm::vec3(50, 50, 50)}) {  // the last: no index refers to it
    lgh::Vertex vertex;
    vertex.position = position;
    triangle.vertices.push_back(vertex);
  }
  triangle.indices = {0, 1, 2, 2, 1, 7};  // 7: past the vertices
  lgh::Mesh mesh;
  mesh.primitives.push_back(triangle);
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, glm::mat4(1.0F)});
  glm::mat4 moved(1.0F);
  moved[3] = glm::vec4(-3.0F, 0.0F, 4.0F, 1.0F);  // translated by (-3, 0, 4)
  scene.instances.push_back({0, moved});
  scene.instances.push_back({5, glm::mat4(1.0F)});  // no such mesh: left out
  scene.computeBounds();
  EXPECT_EQ(scene.bounds.min, glm::vec3(-3.0F, 0.0F, 0.0F));
  EXPECT_EQ(scene.bounds.max, glm::vec3(1.0F, 2.0F, 4.0F));
}

}  // namespace
