#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>

namespace lgh {
namespace {

const Mesh* meshOf(const Scene& scene, const MeshInstance& instance) {
  if (instance.mesh < 0 || static_cast<std::size_t>(instance.mesh) >= scene.meshes.size()) {
    return nullptr;
  }
  return &scene.meshes[static_cast<std::size_t>(instance.mesh)];
}

std::size_t meshTriangles(const Mesh& mesh) {
  std::size_t count = 0;
  for (const Primitive& primitive : mesh.primitives) count += primitive.indices.size() / 3;
  return count;
}

}  // namespace

// Triangles as drawn: a mesh placed by two instances counts twice.
std::size_t Scene::triangleCount() const {
  std::size_t count = 0;
  for (const MeshInstance& instance : instances) {
    if (const Mesh* mesh = meshOf(*this, instance)) count += meshTriangles(*mesh);
  }
  return count;
}

std::size_t Scene::lineAndPointPrimitiveCount() const {
  std::size_t count = 0;
  for (const MeshInstance& instance : instances) {
    if (const Mesh* mesh = meshOf(*this, instance)) count += mesh->linesAndPoints.size();
  }
  return count;
}

// Exact world-space bounds: every referenced vertex of every instance, transformed. Transforming
// the corners of each mesh's local box would be cheaper but loose under rotation, and the bounds
// drive automatic camera framing and the LGH grid.
void Scene::computeBounds() {
  bounds = Bounds{};
  for (const MeshInstance& instance : instances) {
    const Mesh* mesh = meshOf(*this, instance);
    if (mesh == nullptr) continue;
    for (const auto* list : {&mesh->primitives, &mesh->linesAndPoints}) {
      for (const Primitive& primitive : *list) {
        for (std::uint32_t index : primitive.indices) {
          if (index >= primitive.vertices.size()) continue;
          const glm::vec4 world =
              instance.world * glm::vec4(primitive.vertices[index].position, 1.0F);
          bounds.extend(glm::vec3(world));
        }
      }
    }
  }
}

glm::mat3x2 UvTransform::matrix() const {
  // KHR_texture_transform: translation * rotation * scale, with the rotation as the extension's
  // reference code writes it (counter-clockwise in UV space, v pointing down the image).
  const float c = std::cos(rotation);
  const float s = std::sin(rotation);
  glm::mat3x2 m;
  m[0] = glm::vec2(c * scale.x, -s * scale.x);
  m[1] = glm::vec2(s * scale.y, c * scale.y);
  m[2] = offset;
  return m;
}

glm::vec3 Transmission::tint() const {
  if (attenuationDistance <= 0.0F || thicknessFactor <= 0.0F) return glm::vec3(1.0F);
  const glm::vec3 color = glm::clamp(attenuationColor, glm::vec3(1e-4F), glm::vec3(1.0F));
  // Beer-Lambert: attenuationColor is the colour white light has after attenuationDistance.
  return glm::pow(color, glm::vec3(thicknessFactor / attenuationDistance));
}

bool Material::hasLayers() const {
  return clearcoat.factor > 0.0F || sheen.colorFactor != glm::vec3(0.0F) ||
         specular.factor != 1.0F || specular.colorFactor != glm::vec3(1.0F) ||
         specular.ior != 1.5F || specular.texture.valid() || specular.colorTexture.valid() ||
         transmission.factor > 0.0F;
}

}  // namespace lgh

namespace lgh {

std::array<MaterialTextureSlot, kMaterialTextureSlots> materialTextureSlots(const Material& m) {
  return {{
      {&m.baseColorTexture, true},
      {&m.metallicRoughnessTexture, false},
      {&m.normalTexture, false},
      {&m.occlusionTexture, false},
      {&m.emissiveTexture, true},
      {&m.clearcoat.texture, false},
      {&m.clearcoat.roughnessTexture, false},
      {&m.clearcoat.normalTexture, false},
      {&m.sheen.colorTexture, true},
      {&m.sheen.roughnessTexture, false},
      {&m.specular.texture, false},
      {&m.specular.colorTexture, true},
      {&m.transmission.texture, false},
  }};
}

}  // namespace lgh
