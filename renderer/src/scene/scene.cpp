#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace lgh {
namespace {

const Mesh* meshOf(const Scene& scene, const MeshInstance& instance) {
  if (instance.mesh < 0 || static_cast<std::size_t>(instance.mesh) >= scene.meshes.size()) {
    return nullptr;
  }
  return &scene.meshes[static_cast<std::size_t>(instance.mesh)];
}

// The vertices `primitive`'s indices refer to, each once (out-of-range indices left out).
std::vector<std::uint32_t> referencedVertices(const Primitive& primitive) {
  std::vector<bool> seen(primitive.vertices.size(), false);
  std::vector<std::uint32_t> vertices;
  for (std::uint32_t index : primitive.indices) {
    if (index >= seen.size() || seen[index]) continue;
    seen[index] = true;
    vertices.push_back(index);
  }
  return vertices;
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

const Image8* Scene::rgba8Image(int image) const {
  if (image < 0 || static_cast<std::size_t>(image) >= images.size()) return nullptr;
  const Image8& pixels = images[static_cast<std::size_t>(image)];
  if (pixels.width <= 0 || pixels.height <= 0 || pixels.channels != 4) return nullptr;
  return &pixels;
}

// Exact world-space bounds: every referenced vertex of every instance, transformed. Transforming
// the corners of each mesh's local box would be cheaper but loose under rotation, and the bounds
// drive automatic camera framing and the LGH grid. Each primitive's referenced vertices are found
// once, and each instance transforms those alone rather than a vertex per index (a vertex is
// shared by about six triangles in a smooth mesh).
void Scene::computeBounds() {
  bounds = Bounds{};
  std::unordered_map<const Primitive*, std::vector<std::uint32_t>> referenced;
  for (const MeshInstance& instance : instances) {
    const Mesh* mesh = meshOf(*this, instance);
    if (mesh == nullptr) continue;
    forEachPrimitive(*mesh, [&](const Primitive& primitive) {
      auto [found, added] = referenced.try_emplace(&primitive);
      if (added) found->second = referencedVertices(primitive);
      for (std::uint32_t index : found->second) {
        const glm::vec4 world =
            instance.world * glm::vec4(primitive.vertices[index].position, 1.0F);
        bounds.extend(glm::vec3(world));
      }
    });
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
  using U = TextureUsage;
  const bool classic = isClassicModel(m.model);
  // The layers' slots 10 and 11 carry the classic models' gloss and specular maps.
  const MaterialTextureSlot gloss =
      classic ? MaterialTextureSlot{&m.classic.shininessTexture, U::SingleChannel}
              : MaterialTextureSlot{&m.specular.texture, U::Data};
  const TextureRef* specularColor = classic ? &m.classic.specularTexture : &m.specular.colorTexture;
  return {{
      {&m.baseColorTexture, U::Color},
      {&m.metallicRoughnessTexture, U::Data},
      {&m.normalTexture, U::Normal},
      {&m.occlusionTexture, U::SingleChannel},
      {&m.emissiveTexture, U::Color},
      {&m.clearcoat.texture, U::SingleChannel},
      {&m.clearcoat.roughnessTexture, U::Data},
      {&m.clearcoat.normalTexture, U::Normal},
      {&m.sheen.colorTexture, U::Color},
      {&m.sheen.roughnessTexture, U::Data},
      gloss,
      {specularColor, U::Color},
      {&m.transmission.texture, U::SingleChannel},
      {&m.lightMap, U::Color},
      {&m.surface.heightTexture, U::SingleChannel},
  }};
}

std::vector<std::pair<int, TextureUsage>> sampledRgba8Images(const Scene& scene) {
  std::vector<std::pair<int, TextureUsage>> sampled;
  for (const Material& material : scene.materials) {
    for (const MaterialTextureSlot& slot : materialTextureSlots(material)) {
      const int image = slot.texture->image;
      if (scene.rgba8Image(image) == nullptr || scene.compressedImages.count(image) != 0) continue;
      sampled.emplace_back(image, slot.usage);
    }
  }
  return sampled;
}

bool Sampler::operator<(const Sampler& other) const {
  auto key = [](const Sampler& s) {
    return std::make_tuple(s.magFilter, s.minFilter, s.wrapS, s.wrapT, s.borderColor.r,
                           s.borderColor.g, s.borderColor.b, s.borderColor.a, s.anisotropy);
  };
  return key(*this) < key(other);
}

}  // namespace lgh
