// A Scene uploaded to GL: one vertex buffer, one index buffer and one vertex array for all its
// primitives (triangles, lines and points; each draw names its range and base vertex),
// textures with mipmaps per use (sRGB colour, data, normal map, one channel; block-compressed when
// asked or loaded so: scene/texture_upload.hpp), and sampler objects from the samplers the
// materials ask for (glTF's, or a request's: wrap modes with a border colour, filters,
// anisotropy up to the device's maximum). Textures and samplers are made on first use, since a
// request's material parameters may name textures and sampling no material of the asset uses.
// Owned by the scene cache; passes only draw it.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl_objects.hpp"
#include "gl/readback_buffers.hpp"
#include "gl/recycled_objects.hpp"
#include "scene/geometry_layout.hpp"
#include "scene/scene.hpp"
#include "scene/scene_mip_chains.hpp"
#include "scene/staged_scene.hpp"
#include "scene/texture_upload.hpp"

namespace lgh {

struct GpuSceneOptions {
  float maxAnisotropy = 1.0F;  // the device's
  TextureCompression compression = TextureCompression::None;
  // The device's formats, when the caller knows them (the scene cache asks once per context:
  // four format queries per new scene were render-thread time); queried when not.
  std::optional<TextureCapabilities> capabilities;
  // Where RGBA8 textures and the geometry's buffers take their storage and give it back when the
  // scene is freed (null: each has its own). Only for scenes made and freed on one thread.
  std::shared_ptr<gl::RecycledTextures> recycledTextures;
  std::shared_ptr<gl::RecycledBuffers> recycledBuffers;
};

class GpuScene {
 public:
  // Keeps a reference to `scene` (its images upload on first use): the cache entry owns both.
  // `staged` (may be null): the scene's bytes in staging memory, read by the GPU copies this
  // issues; the caller retires its region after construction. `mipChains` (may be null): the
  // textures' CPU-built levels made ahead (scene/scene_mip_chains.hpp), read during construction.
  GpuScene(const Scene& scene, const GpuSceneOptions& options, const StagedScene* staged = nullptr,
           const SceneMipChains* mipChains = nullptr);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  // The upload on another context of the render context's share group (gl/gl_worker.hpp): the
  // buffers, textures and samplers, behind a fence; vertex arrays are per context, and are left
  // to adopt(). Nothing is drawn from it before adopt().
  static std::unique_ptr<GpuScene> uploadShared(const Scene& scene, const GpuSceneOptions& options);
  // On the render thread, once, for a scene from uploadShared(): makes the render context's GPU
  // queue wait for the upload's fence (the CPU does not wait) and makes the vertex arrays.
  void adopt();
  // On the render thread: deletes the vertex arrays, so that the rest (shared objects only) may
  // be freed on another context of the share group.
  void releaseVertexArrays();

  struct DrawItem {
    GLuint vertexArray;
    GLsizei indexCount;
    GLuint firstIndex;  // in the scene's index buffer
    GLint baseVertex;   // added to each index: the primitive's first vertex
    int material;       // -1: default material
    glm::mat4 world;
    Topology topology = Topology::Triangles;
    bool unlit = false;                    // lines and points without normals
    bool tangents = false;                 // the vertices carry a tangent frame
    const Primitive* primitive = nullptr;  // the scene's, for centreOf
    // The item's place in drawItems(), and so its base instance: the vertex array's per-draw
    // attributes (kDrawTransformLocation) read its transforms at that index.
    GLuint drawIndex = 0;
    bool mirrored = false;  // the world matrix flips the winding (negative determinant)
  };
  // The per-draw attributes of the vertex array, from the scene's buffer of draw transforms
  // (one per draw item, instanced with divisor 1): the world matrix's columns at locations 6-9 and
  // the normal matrix's (inverse transpose) at 10-12, as glsl/gbuffer.vert declares them. A draw
  // picks its own with its base instance, so no uniform changes between draws.
  static constexpr GLuint kDrawTransformLocation = 6;
  // The world-space centre of an item's bounds, for sorting blended surfaces back to front. Only
  // blended items need it, so it is computed when asked: one pass over the primitive's vertices,
  // which for every item of a large scene was a noticeable part of a new scene's upload on the
  // render thread.
  static glm::vec3 centreOf(const DrawItem& item);
  // Every primitive of every instance.
  const std::vector<DrawItem>& drawItems() const { return drawItems_; }

  // Texture and sampler names for a material slot; {0, 0} when the slot has no texture.
  struct BoundTexture {
    GLuint texture = 0;
    GLuint sampler = 0;
    bool twoChannel = false;  // a BC5 normal map
  };
  BoundTexture texture(const TextureRef& ref, TextureUsage usage);

  std::size_t gpuBytes() const { return geometryBytes_ + textureBytes_; }

  // What the textures take: for the result's paths.texture_memory.
  struct TextureMemory {
    std::size_t bytes = 0;
    std::size_t uncompressedBytes = 0;  // the same textures as RGBA8
    int textures = 0;
    int compressed = 0;
  };
  TextureMemory textureMemory() const { return memory_; }
  // Warnings of texture uploads since the last call (formats the device lacks).
  std::vector<std::string> takeWarnings();
  float maxAnisotropy() const { return options_.maxAnisotropy; }

 private:
  struct VertexArraysLater {};
  GpuScene(const Scene& scene, const GpuSceneOptions& options, VertexArraysLater later,
           const StagedScene* staged = nullptr, const SceneMipChains* mipChains = nullptr);
  void makeVertexArrays();

  struct UploadedImage {
    gl::RecycledTexture texture;
    bool twoChannel = false;
  };
  GLuint samplerFor(const Sampler& sampler);
  // `staged` (may be null): the scene's pixels in staging memory, while it is being made.
  BoundTexture texture(const TextureRef& ref, TextureUsage usage, const StagedScene* staged);
  const UploadedImage* imageTexture(int image, TextureUsage usage, const StagedScene* staged);
  // One buffer pair for the whole scene: a new scene's allocations and its first draws'
  // vertex-array validation were per primitive before, which on NVIDIA's driver made most of
  // a many-part asset's upload.
  void uploadGeometry(const Scene& scene, const GeometryLayout& layout, const StagedScene* staged);
  void uploadDrawTransforms();
  // A buffer with at least `bytes` usable bytes (recycled up to kMaxRecycledBufferBytes).
  gl::RecycledBuffer takeBuffer(GLsizeiptr bytes);
  static constexpr GLsizeiptr kMaxRecycledBufferBytes = GLsizeiptr{16} << 20;

  // The levels made ahead, while the constructor uploads the materials' textures.
  const SceneMipChains* aheadMipChains_ = nullptr;
  const Scene& scene_;
  GpuSceneOptions options_;
  TextureCapabilities capabilities_;
  std::vector<DrawItem> drawItems_;
  gl::RecycledBuffer vertices_;
  gl::RecycledBuffer indices_;
  gl::RecycledBuffer drawTransforms_;  // per draw item (kDrawTransformLocation)
  gl::VertexArray vertexArray_ = gl::VertexArray::empty();  // made by makeVertexArrays()
  bool vertexArrays_ = false;
  gl::Fence uploaded_;  // uploadShared()'s, until adopt()
  // By (image, kind): the kinds an upload distinguishes (without compression colour and data).
  std::map<std::pair<int, int>, UploadedImage> textures_;
  std::map<Sampler, gl::SamplerObject> samplers_;
  std::size_t geometryBytes_ = 0;
  std::size_t textureBytes_ = 0;
  TextureMemory memory_;
  std::vector<std::string> warnings_;
};

}  // namespace lgh
