// A scene's triangles and materials as the GL passes that resolve ray hits read them
// (glsl/include/hit_surface.glsl, mirrored here): object-space vertices (position, normal, both
// texture coordinates, colour) and indices packed exactly as the acceleration structures pack
// them (vk::packGeometry), so a hit's (instance, geometry, primitive) names its triangle; the
// instances' transforms; the materials (gi_material.hpp) with their base-colour textures in an
// albedo array; and, on the CPU, the emissive triangles that light paths start from. Built once
// per cached scene (CachedScene::hitGeometry) by the first frame with GI, from the frame's
// materials (MaterialTable: the scene's, extras.lgh included, with the request's `materials`
// applied); built again when a frame's materials differ in what light paths read
// (sameForLightPaths), so that a request's overrides colour the indirect light too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gi/albedo_array.hpp"
#include "gi/gi_material.hpp"
#include "gl/gl_objects.hpp"
#include "scene/scene_cache.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh {

struct HitVertexGpu {  // HitVertex, 64 bytes
  glm::vec4 position{0.0F};
  glm::vec4 normal{0.0F};
  glm::vec4 uv{0.0F};  // xy: TEXCOORD_0, zw: TEXCOORD_1
  glm::vec4 color{1.0F};
};
static_assert(sizeof(HitVertexGpu) == 64, "HitVertexGpu must match HitVertex (std430)");

struct HitGeometryGpu {  // HitGeometry, 16 bytes
  std::uint32_t firstVertex = 0;
  std::uint32_t firstIndex = 0;
  std::uint32_t material = 0;
  std::uint32_t triangleCount = 0;
};
static_assert(sizeof(HitGeometryGpu) == 16, "HitGeometryGpu must match HitGeometry (std430)");

struct HitInstanceGpu {  // HitInstance, 144 bytes
  glm::mat4 world{1.0F};
  glm::mat4 normalWorld{1.0F};
  glm::uvec4 geometries{0U};  // x: first geometry of its mesh, y: their count, z: 1 mirrored
};
static_assert(sizeof(HitInstanceGpu) == 144, "HitInstanceGpu must match HitInstance (std430)");

// An emissive triangle in world space: an area light of the light paths.
struct EmissiveTriangle {
  glm::vec3 vertex0{0.0F};
  glm::vec3 vertex1{0.0F};
  glm::vec3 vertex2{0.0F};
  glm::vec3 normal{0.0F, 1.0F, 0.0F};  // unit, of the front (counter-clockwise) side
  glm::vec3 radiance{0.0F};
  float area = 0.0F;
  bool doubleSided = false;
};

class HitGeometry final : public SceneAttachment {
 public:
  HitGeometry(const Scene& scene, const std::vector<Material>& materials);

  // The cached scene's hit geometry for the frame's `materials` (one per scene material), built
  // on the first call and again when `materials` differ from those it was built with.
  static const HitGeometry& of(const CachedScene& scene, const std::vector<Material>& materials);

  // Binds the buffers and the albedo array at their GI slots (glsl/include/slots.glsl).
  void bind() const;
  // Unbinds the albedo array's sampler (texture units are shared with other passes).
  static void unbind();

  // The same arrays for Vulkan's light paths (vk/shadow_tracer.hpp, LightPathScene): kept on
  // the CPU beside the GL buffers, so that a new tracer (after a device reset) can upload them
  // again; the id is this object's, unique in the process.
  vk::LightPathScene lightPathScene() const;

  const std::vector<EmissiveTriangle>& emissiveTriangles() const { return emissive_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  std::size_t triangleCount() const { return triangles_; }
  std::size_t gpuBytes() const override { return gpuBytes_; }

 private:
  void upload(GLuint buffer, const void* data, std::size_t bytes);
  bool builtWith(const std::vector<Material>& materials) const;

  std::vector<Material> materialsBuiltWith_;
  std::vector<std::string> warnings_;
  AlbedoArray albedo_;
  gl::Buffer vertices_;
  gl::Buffer indices_;
  gl::Buffer geometries_;
  gl::Buffer instances_;
  gl::Buffer materials_;
  std::uint64_t id_;
  std::vector<HitVertexGpu> vertexArray_;
  std::vector<std::uint32_t> indexArray_;
  std::vector<HitGeometryGpu> geometryArray_;
  std::vector<HitInstanceGpu> instanceArray_;
  std::vector<GiMaterialGpu> materialArray_;
  std::vector<EmissiveTriangle> emissive_;
  std::size_t triangles_ = 0;
  std::size_t gpuBytes_ = 0;
};

}  // namespace lgh
