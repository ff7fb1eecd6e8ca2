// A Scene uploaded to GL: vertex/index buffers per primitive (triangles, lines and points),
// textures with mipmaps (sRGB or linear as the material slot needs), sampler objects from the glTF
// samplers with anisotropic filtering. Owned by the scene cache; passes only draw it.
#pragma once

#include <functional>
#include <map>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl_objects.hpp"
#include "scene/scene.hpp"

namespace lgh {

class GpuScene {
 public:
  GpuScene(const Scene& scene, float maxAnisotropy);

  struct DrawItem {
    GLuint vertexArray;
    GLsizei indexCount;
    int material;  // -1: default material
    glm::mat4 world;
    Topology topology = Topology::Triangles;
    bool unlit = false;  // lines and points without normals
  };
  // Every primitive of every instance.
  const std::vector<DrawItem>& drawItems() const { return drawItems_; }

  // Texture and sampler names for a material slot; {0, 0} when the slot has no texture.
  struct BoundTexture {
    GLuint texture = 0;
    GLuint sampler = 0;
  };
  BoundTexture texture(const TextureRef& ref, bool srgb) const;

  std::size_t gpuBytes() const { return gpuBytes_; }

 private:
  struct GpuPrimitive {
    gl::VertexArray vertexArray;
    gl::Buffer vertices;
    gl::Buffer indices;
    GLsizei indexCount = 0;
  };
  GLuint samplerFor(const Sampler& sampler);
  void uploadTextures(const Scene& scene);
  void uploadPrimitive(const Primitive& primitive, GpuPrimitive& gpu);

  std::vector<std::vector<GpuPrimitive>> meshes_;
  std::vector<DrawItem> drawItems_;
  // Per image: [0] linear, [1] sRGB (only the variants the materials use are created).
  std::vector<std::array<gl::Texture, 2>> textures_;
  std::map<std::tuple<int, int, int, int>, gl::SamplerObject> samplers_;
  std::map<std::pair<int, bool>, BoundTexture> bindings_;
  float maxAnisotropy_ = 1.0F;
  std::size_t gpuBytes_ = 0;
};

}  // namespace lgh
