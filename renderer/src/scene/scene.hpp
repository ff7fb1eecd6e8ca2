// CPU-side scene data: what a glTF asset or the built-in demo becomes before upload. Knows no GL
// and no passes; the GPU upload (gpu_scene) and, later, the Vulkan acceleration structures are
// built from it.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene/block_compression.hpp"

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

// How a primitive's indices are read: glTF's seven modes arrive as one of these three (strips,
// fans and loops are unrolled into lists by the loader).
enum class Topology { Triangles, Lines, Points };

// One glTF primitive: an indexed list (non-indexed input gets 0..n-1) of triangles, lines (two
// indices each) or points.
struct Primitive {
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;
  int material = -1;  // -1: default material
  Topology topology = Topology::Triangles;
  // Lines and points without NORMAL are drawn unlit, as the glTF specification asks.
  bool unlit = false;
  // Whether Vertex::tangent holds a real tangent frame (the asset's or MikkTSpace's). Without one,
  // the techniques that need a frame (parallax, relief) derive it per pixel from the derivatives
  // of position and texture coordinates.
  bool tangents = false;
};

struct Mesh {
  std::string name;
  // Triangle lists: what every consumer of surfaces reads (VPL placement, ray tracing).
  std::vector<Primitive> primitives;
  // Lines and points (topology Lines or Points): drawn into the G-buffer, framed by the camera.
  std::vector<Primitive> linesAndPoints;
};

// Every primitive of `mesh`: its triangle lists, then its lines and points.
template <typename Fn>
void forEachPrimitive(const Mesh& mesh, Fn&& fn) {
  for (const auto* list : {&mesh.primitives, &mesh.linesAndPoints}) {
    for (const Primitive& primitive : *list) fn(primitive);
  }
}

// A mesh placed in the world by the flattened node hierarchy.
struct MeshInstance {
  int mesh = 0;
  glm::mat4 world{1.0F};
};

// glTF sampler values (GL enums as glTF stores them), plus what glTF cannot say: clamp to border
// (GL_CLAMP_TO_BORDER) with its colour, and the anisotropy (0: the device's maximum).
struct Sampler {
  int magFilter = 0x2601;  // GL_LINEAR
  int minFilter = 0x2703;  // GL_LINEAR_MIPMAP_LINEAR
  int wrapS = 0x2901;      // GL_REPEAT
  int wrapT = 0x2901;
  glm::vec4 borderColor{0.0F};
  float anisotropy = 0.0F;
  bool operator<(const Sampler& other) const;
};

// KHR_texture_transform: uv' = T * R * S * uv (offset, rotation, scale); identity by default.
struct UvTransform {
  glm::vec2 offset{0.0F};
  float rotation = 0.0F;  // radians, counter-clockwise in UV space
  glm::vec2 scale{1.0F};
  // The 3x2 affine matrix (3 columns of vec2) the shader multiplies vec3(uv, 1) by.
  glm::mat3x2 matrix() const;
};

struct TextureRef {
  int image = -1;  // index into Scene::images; -1: none
  int texCoord = 0;
  Sampler sampler;
  UvTransform transform;
  bool valid() const { return image >= 0; }
};

// KHR_materials_clearcoat: a dielectric coat (IOR 1.5) over the base material.
struct Clearcoat {
  float factor = 0.0F;
  float roughness = 0.0F;
  TextureRef texture;           // R
  TextureRef roughnessTexture;  // G
  TextureRef normalTexture;
  float normalScale = 1.0F;
};

// KHR_materials_sheen: a retro-reflective cloth lobe (Charlie distribution).
struct Sheen {
  glm::vec3 colorFactor{0.0F};
  float roughnessFactor = 0.0F;
  TextureRef colorTexture;      // sRGB
  TextureRef roughnessTexture;  // A
};

// KHR_materials_specular and KHR_materials_ior: the dielectric Fresnel of the base.
struct Specular {
  float factor = 1.0F;
  glm::vec3 colorFactor{1.0F};
  float ior = 1.5F;
  TextureRef texture;       // A
  TextureRef colorTexture;  // sRGB
};

// KHR_materials_transmission and KHR_materials_volume, approximated (docs/MATERIALS.md): the
// transmitted share of the diffuse lobe is lit from behind the surface, tinted by the volume's
// attenuation over its thickness; what lies behind the surface is not seen through it.
struct Transmission {
  float factor = 0.0F;
  TextureRef texture;  // R
  float thicknessFactor = 0.0F;
  glm::vec3 attenuationColor{1.0F};
  float attenuationDistance = 0.0F;  // 0: infinite (no attenuation)
  // The volume's tint at the surface's thickness, per channel in 0..1.
  glm::vec3 tint() const;
};

// The lecture's classic models (Phong, Blinn-Phong, Oren-Nayar, Cook-Torrance): what they take
// beside the diffuse colour (Material::baseColorFactor) and the emission (emissiveFactor).
struct ClassicMaterial {
  std::optional<glm::vec3> ambient;  // ambient_material; unset: the diffuse colour (textured)
  glm::vec3 specular{0.5F};          // specular_material (Phong, Blinn-Phong)
  float shininess = 32.0F;           // m_shi
  float sigma = 0.3F;                // Oren-Nayar roughness, radians
  float m = 0.3F;                    // Cook-Torrance roughness: RMS slope of the microfacets
  glm::vec3 f0{0.04F};               // Cook-Torrance Fresnel reflectance at normal incidence
  TextureRef specularTexture;        // specular map, sRGB: multiplies specular (Cook-Torrance: F)
  TextureRef shininessTexture;       // gloss map, R: multiplies shininess (pixel shading)
  ShadingMode shading = ShadingMode::Pixel;
};

// Surface detail from the normal and height maps (SurfaceDetail says which technique).
struct SurfaceDetailMaterial {
  SurfaceDetail technique = SurfaceDetail::Normal;
  TextureRef heightTexture;  // R; 1 is the top of the surface
  // Bump and displacement: the height of R = 1 in world units. Parallax and relief: the lecture's
  // scale s in texture units (relief: the depth of the height field).
  float heightScale = 0.05F;
  std::optional<float> parallaxBias;  // the lecture's b; unset: heightScale / 2
  int reliefLinearSteps = 32;
  int reliefBinarySteps = 6;
  bool reliefSelfShadow = true;
  bool reliefSilhouettes = false;
  float tessellationPixels = 8.0F;  // displacement: target edge length of a patch on screen
  int tessellationMaxLevel = 64;
  bool usesHeight() const { return technique >= SurfaceDetail::Bump && heightTexture.valid(); }
};

// glTF PBR metallic-roughness material, with the KHR_materials_* extensions this renderer knows.
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
  MaterialModel model = MaterialModel::MetallicRoughness;
  Clearcoat clearcoat;
  Sheen sheen;
  Specular specular;
  Transmission transmission;
  ClassicMaterial classic;
  SurfaceDetailMaterial surface;
  TextureRef lightMap;  // precomputed illumination (usually on TEXCOORD_1), multiplied in
  float lightMapStrength = 1.0F;
  bool bicubic = false;  // textures filtered bicubically in the shader
  // Whether any layer above differs from plain metallic-roughness (the G-buffer then carries them).
  bool hasLayers() const;
};

// What a texture slot holds, which decides its GL format: sRGB colour, linear data (RGBA), a
// tangent-space normal map (two channels suffice: BC5 when compressed) or one channel (R: BC4).
enum class TextureUsage : std::uint8_t { Color, Data, Normal, SingleChannel };

// Every texture of a material in the G-buffer shader's slot order (texture unit = index; see
// glsl/include/material_sampling.glsl), with what it holds. Slots 10 and 11 hold the
// KHR_materials_specular textures of metallic-roughness materials and the gloss and specular
// maps of the classic models.
struct MaterialTextureSlot {
  const TextureRef* texture;
  TextureUsage usage;
};
inline constexpr std::size_t kMaterialTextureSlots = 15;
std::array<MaterialTextureSlot, kMaterialTextureSlots> materialTextureSlots(
    const Material& material);

// Every texture reference of a material (Material& or const Material&), in one fixed order: the
// scene parser worker's messages carry them in it; the sampling overrides change them all. Both
// specular pairs are here (the shader's slots 10 and 11 hold one of them): two more than slots.
template <typename M>
auto allMaterialTextures(M& m) {
  return std::array{&m.baseColorTexture,
                    &m.metallicRoughnessTexture,
                    &m.normalTexture,
                    &m.occlusionTexture,
                    &m.emissiveTexture,
                    &m.clearcoat.texture,
                    &m.clearcoat.roughnessTexture,
                    &m.clearcoat.normalTexture,
                    &m.sheen.colorTexture,
                    &m.sheen.roughnessTexture,
                    &m.specular.texture,
                    &m.specular.colorTexture,
                    &m.transmission.texture,
                    &m.classic.specularTexture,
                    &m.classic.shininessTexture,
                    &m.surface.heightTexture,
                    &m.lightMap};
}

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
  std::vector<Image8> images;  // decoded RGBA8
  // Block-compressed payloads of images loaded precompressed (DDS), by index into images (which
  // holds their decoded pixels for the CPU's use).
  std::map<int, BlockCompressedImage> compressedImages;
  // The asset's textures (glTF's textures array; the demo's own list): what material parameters
  // of a request or of glTF extras name by index. An entry whose image failed is invalid.
  std::vector<TextureRef> textures;
  std::vector<LightDesc> lights;  // world space
  std::vector<SceneCamera> cameras;
  Bounds bounds;                      // world space, over all instances
  std::vector<std::string> warnings;  // repairs made while loading (shown in the result)

  std::size_t triangleCount() const;
  // Image `image` when it exists as RGBA8 pixels (the only layout textures are uploaded from),
  // else null.
  const Image8* rgba8Image(int image) const;
  // Lines and points as drawn (instances count), for the result's statistics.
  std::size_t lineAndPointPrimitiveCount() const;
  void computeBounds();
};

// Every (image, usage) the scene's materials sample that exists as RGBA8 pixels and did not arrive
// block-compressed: what an upload without texture compression makes textures of, in material and
// slot order (an image may come more than once).
std::vector<std::pair<int, TextureUsage>> sampledRgba8Images(const Scene& scene);

}  // namespace lgh
