// CPU-side scene data: what a glTF asset or the built-in demo becomes before upload. Knows no GL
// and no passes; the GPU upload (gpu_scene) and, later, the Vulkan acceleration structures are
// built from it.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "lgh/image.hpp"
#include "lgh/request.hpp"

namespace lgh {

struct Vertex {
  glm::vec3 position{0.0F};
  glm::vec3 normal{0.0F, 1.0F, 0.0F};
  glm::vec4 tangent{1.0F, 0.0F, 0.0F, 1.0F};  // xyz + handedness sign, MikkTSpace-style
  glm::vec2 uv0{0.0F};
  glm::vec2 uv1{0.0F};
  glm::vec4 color{1.0F};  // COLOR_0, white when absent
};

// One glTF primitive: an indexed triangle list (non-indexed input gets 0..n-1).
struct Primitive {
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;
  int material = -1;  // -1: default material
};

struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
};

// A mesh placed in the world by the flattened node hierarchy.
struct MeshInstance {
  int mesh = 0;
  glm::mat4 world{1.0F};
};

enum class AlphaMode { Opaque, Mask, Blend };

// glTF sampler values (GL enums as glTF stores them).
struct Sampler {
  int magFilter = 0x2601;  // GL_LINEAR
  int minFilter = 0x2703;  // GL_LINEAR_MIPMAP_LINEAR
  int wrapS = 0x2901;      // GL_REPEAT
  int wrapT = 0x2901;
};

struct TextureRef {
  int image = -1;  // index into Scene::images; -1: none
  int texCoord = 0;
  Sampler sampler;
  bool valid() const { return image >= 0; }
};

// glTF PBR metallic-roughness material.
struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0F};
  float metallicFactor = 1.0F;
  float roughnessFactor = 1.0F;
  glm::vec3 emissiveFactor{0.0F};
  float normalScale = 1.0F;
  float occlusionStrength = 1.0F;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5F;
  bool doubleSided = false;
  TextureRef baseColorTexture;          // sRGB
  TextureRef metallicRoughnessTexture;  // linear, G = roughness, B = metallic
  TextureRef normalTexture;             // linear, tangent space
  TextureRef occlusionTexture;          // linear, R
  TextureRef emissiveTexture;           // sRGB
};

struct SceneCamera {
  std::string name;
  bool perspective = true;
  float yfov = 0.8F;         // radians
  float aspectRatio = 0.0F;  // 0: from the output size
  float znear = 0.1F;
  float zfar = 0.0F;               // 0: infinite in glTF; derived from bounds here
  float xmag = 1.0F, ymag = 1.0F;  // orthographic
  glm::mat4 world{1.0F};
};

struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{-std::numeric_limits<float>::max()};
  bool empty() const { return min.x > max.x; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  glm::vec3 center() const { return (min + max) * 0.5F; }
  glm::vec3 size() const { return max - min; }
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<MeshInstance> instances;
  std::vector<Material> materials;
  std::vector<Image8> images;     // decoded RGBA8
  std::vector<LightDesc> lights;  // world space
  std::vector<SceneCamera> cameras;
  Bounds bounds;                      // world space, over all instances
  std::vector<std::string> warnings;  // repairs made while loading (shown in the result)

  std::size_t triangleCount() const;
  void computeBounds();
};

}  // namespace lgh
