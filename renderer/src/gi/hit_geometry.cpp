#include "gi/hit_geometry.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>

#include <spdlog/spdlog.h>
#include <glm/gtc/matrix_inverse.hpp>

#include "gi/gi_material.hpp"
#include "gl/slots.hpp"
#include "lgh/error.hpp"
#include "vk/scene_geometry.hpp"

namespace lgh {
namespace {

std::uint64_t nextHitGeometryId() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1);
}

template <typename T>
std::span<const std::byte> bytesOf(const std::vector<T>& values) {
  return std::as_bytes(std::span(values));
}

// Layers of the albedo array at most: 256 x 256 RGBA with mipmaps is 350 KB a layer.
constexpr int kMaxAlbedoLayers = 256;

float luminance(const glm::vec3& rgb) {
  return glm::dot(rgb, glm::vec3(0.2126F, 0.7152F, 0.0722F));
}

const Material& materialOf(const std::vector<Material>& materials, int index) {
  static const Material kDefault;
  if (index < 0 || static_cast<std::size_t>(index) >= materials.size()) return kDefault;
  return materials[static_cast<std::size_t>(index)];
}

// The linear mean colour of each image some material emits with.
std::map<int, glm::vec3> emissiveMeans(const Scene& scene, const std::vector<Material>& materials) {
  std::map<int, glm::vec3> means;
  for (const Material& material : materials) {
    const int image = material.emissiveTexture.image;
    if (image < 0 || static_cast<std::size_t>(image) >= scene.images.size()) continue;
    if (!means.contains(image)) {
      means[image] = meanLinearColor(scene.images[static_cast<std::size_t>(image)]);
    }
  }
  return means;
}

glm::vec3 emissiveMeanOf(const std::map<int, glm::vec3>& means, const Material& material) {
  const auto it = means.find(material.emissiveTexture.image);
  return it == means.end() ? glm::vec3(1.0F) : it->second;
}

std::vector<HitVertexGpu> packVertices(const Scene& scene, const vk::PackedGeometry& packed) {
  std::vector<HitVertexGpu> vertices;
  vertices.reserve(packed.positions.size());
  for (std::size_t m = 0; m < packed.meshes.size(); ++m) {
    for (const vk::PackedPrimitive& placed : packed.meshes[m].primitives) {
      if (vertices.size() != placed.firstVertex) {
        throw Error(ErrorCode::Internal, "gi: hit geometry out of step with the packed triangles");
      }
      for (const Vertex& vertex : scene.meshes[m].primitives[placed.sourcePrimitive].vertices) {
        vertices.push_back({glm::vec4(vertex.position, 1.0F), glm::vec4(vertex.normal, 0.0F),
                            glm::vec4(vertex.uv0, vertex.uv1), vertex.color});
      }
    }
  }
  return vertices;
}

void addEmissiveTriangles(const Scene& scene, const std::vector<Material>& materials,
                          const vk::PackedGeometry& packed, const std::map<int, glm::vec3>& means,
                          const MeshInstance& instance, std::vector<EmissiveTriangle>& out) {
  const auto mesh = static_cast<std::size_t>(instance.mesh);
  // glTF: a negative determinant flips which side of a triangle is its front.
  const float side = glm::determinant(glm::mat3(instance.world)) < 0.0F ? -1.0F : 1.0F;
  for (const vk::PackedPrimitive& placed : packed.meshes[mesh].primitives) {
    const Primitive& primitive = scene.meshes[mesh].primitives[placed.sourcePrimitive];
    const Material& material = materialOf(materials, primitive.material);
    const glm::vec3 radiance = emittedRadiance(material, emissiveMeanOf(means, material));
    if (!(luminance(radiance) > 0.0F)) continue;
    for (std::uint32_t t = 0; t < placed.triangleCount; ++t) {
      EmissiveTriangle triangle;
      glm::vec3* corners[3] = {&triangle.vertex0, &triangle.vertex1, &triangle.vertex2};
      for (std::uint32_t k = 0; k < 3; ++k) {
        const glm::vec3 local =
            packed.positions[placed.firstVertex + packed.indices[placed.firstIndex + 3 * t + k]];
        *corners[k] = glm::vec3(instance.world * glm::vec4(local, 1.0F));
      }
      const glm::vec3 crossed =
          glm::cross(triangle.vertex1 - triangle.vertex0, triangle.vertex2 - triangle.vertex0);
      triangle.area = 0.5F * glm::length(crossed);
      if (!(triangle.area > 0.0F) || !std::isfinite(triangle.area)) continue;
      triangle.normal = side * glm::normalize(crossed);
      triangle.radiance = radiance;
      triangle.doubleSided = material.doubleSided;
      out.push_back(triangle);
    }
  }
}

}  // namespace

HitGeometry::HitGeometry(const Scene& scene, const std::vector<Material>& materials)
    : materialsBuiltWith_(materials),
      albedo_(
          scene, materials,
          [] {
            GLint layers = 0;
            glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &layers);
            return std::min(kMaxAlbedoLayers, std::max(layers, 1));
          }(),
          warnings_),
      id_(nextHitGeometryId()) {
  const vk::PackedGeometry packed = vk::packGeometry(scene);
  triangles_ = packed.triangleCount;
  std::vector<HitVertexGpu> vertices = packVertices(scene, packed);

  std::vector<std::uint32_t> firstGeometryOfMesh(packed.meshes.size(), 0);
  std::vector<HitGeometryGpu> geometries;
  const auto defaultMaterial = static_cast<std::uint32_t>(materials.size());
  for (std::size_t m = 0; m < packed.meshes.size(); ++m) {
    firstGeometryOfMesh[m] = static_cast<std::uint32_t>(geometries.size());
    for (const vk::PackedPrimitive& placed : packed.meshes[m].primitives) {
      const int material = scene.meshes[m].primitives[placed.sourcePrimitive].material;
      const bool known = material >= 0 && static_cast<std::size_t>(material) < materials.size();
      geometries.push_back({placed.firstVertex, placed.firstIndex,
                            known ? static_cast<std::uint32_t>(material) : defaultMaterial,
                            placed.triangleCount});
    }
  }

  std::vector<HitInstanceGpu> instances(scene.instances.size());
  const std::map<int, glm::vec3> means = emissiveMeans(scene, materials);
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const MeshInstance& instance = scene.instances[i];
    instances[i].world = instance.world;
    instances[i].normalWorld = glm::inverseTranspose(instance.world);
    if (instance.mesh < 0 || static_cast<std::size_t>(instance.mesh) >= packed.meshes.size()) {
      continue;
    }
    const auto mesh = static_cast<std::size_t>(instance.mesh);
    instances[i].geometries =
        glm::uvec4(firstGeometryOfMesh[mesh],
                   static_cast<std::uint32_t>(packed.meshes[mesh].primitives.size()), 0U, 0U);
    addEmissiveTriangles(scene, materials, packed, means, instance, emissive_);
  }

  std::vector<GiMaterialGpu> packedMaterials;
  packedMaterials.reserve(materials.size() + 1);
  for (const Material& material : materials) {
    packedMaterials.push_back(packGiMaterial(material,
                                             albedo_.layerOf(material.baseColorTexture.image),
                                             emissiveMeanOf(means, material)));
  }
  packedMaterials.push_back(packGiMaterial(Material{}, -1, glm::vec3(1.0F)));

  upload(vertices_.id(), vertices.data(), vertices.size() * sizeof(HitVertexGpu));
  upload(indices_.id(), packed.indices.data(), packed.indices.size() * sizeof(std::uint32_t));
  upload(geometries_.id(), geometries.data(), geometries.size() * sizeof(HitGeometryGpu));
  upload(instances_.id(), instances.data(), instances.size() * sizeof(HitInstanceGpu));
  upload(materials_.id(), packedMaterials.data(), packedMaterials.size() * sizeof(GiMaterialGpu));
  vertexArray_ = std::move(vertices);
  indexArray_ = packed.indices;
  geometryArray_ = std::move(geometries);
  instanceArray_ = std::move(instances);
  materialArray_ = std::move(packedMaterials);
  gpuBytes_ += albedo_.gpuBytes();
  spdlog::debug("gi: hit geometry of '{}': {} triangles, {} emissive, {:.1f} MB", scene.name,
                triangles_, emissive_.size(), static_cast<double>(gpuBytes_) / 1e6);
}

void HitGeometry::upload(GLuint buffer, const void* data, std::size_t bytes) {
  // Never empty: a buffer of 0 bytes cannot be bound.
  const auto size = static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16));
  glNamedBufferStorage(buffer, size, nullptr, GL_DYNAMIC_STORAGE_BIT);
  if (bytes > 0) glNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(bytes), data);
  gpuBytes_ += static_cast<std::size_t>(size);
}

vk::LightPathScene HitGeometry::lightPathScene() const {
  return {.id = id_,
          .vertices = bytesOf(vertexArray_),
          .indices = bytesOf(indexArray_),
          .geometries = bytesOf(geometryArray_),
          .instances = bytesOf(instanceArray_),
          .materials = bytesOf(materialArray_),
          .albedoTexels = albedo_.texels()};
}

bool HitGeometry::builtWith(const std::vector<Material>& materials) const {
  return std::equal(materials.begin(), materials.end(), materialsBuiltWith_.begin(),
                    materialsBuiltWith_.end(), sameForLightPaths);
}

const HitGeometry& HitGeometry::of(const CachedScene& scene,
                                   const std::vector<Material>& materials) {
  const auto* built = static_cast<const HitGeometry*>(scene.hitGeometry.get());
  if (built == nullptr || !built->builtWith(materials)) {
    if (built != nullptr) {
      spdlog::debug("gi: the frame's materials differ from the hit geometry's: building it again");
    }
    scene.hitGeometry = std::make_unique<HitGeometry>(scene.scene, materials);
  }
  return static_cast<const HitGeometry&>(*scene.hitGeometry);
}

void HitGeometry::bind() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_VERTICES, vertices_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_INDICES, indices_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_GEOMETRIES, geometries_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_INSTANCES, instances_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_MATERIALS, materials_.id());
  glBindTextureUnit(LGH_UNIT_GI_ALBEDO, albedo_.texture());
  glBindSampler(LGH_UNIT_GI_ALBEDO, albedo_.sampler());
}

void HitGeometry::unbind() {
  glBindSampler(LGH_UNIT_GI_ALBEDO, 0);
  glBindTextureUnit(LGH_UNIT_GI_ALBEDO, 0);
}

}  // namespace lgh
