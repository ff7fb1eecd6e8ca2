#include "scene/gpu_scene.hpp"

#include <cmath>
#include <cstddef>

namespace lgh {
namespace {

void setAttribute(GLuint vao, GLuint location, GLint size, GLuint offset) {
  glEnableVertexArrayAttrib(vao, location);
  glVertexArrayAttribFormat(vao, location, size, GL_FLOAT, GL_FALSE, offset);
  glVertexArrayAttribBinding(vao, location, 0);
}

bool usesMipmaps(int minFilter) {
  return minFilter == GL_NEAREST_MIPMAP_NEAREST || minFilter == GL_LINEAR_MIPMAP_NEAREST ||
         minFilter == GL_NEAREST_MIPMAP_LINEAR || minFilter == GL_LINEAR_MIPMAP_LINEAR;
}

int mipLevels(int width, int height) {
  return 1 + static_cast<int>(std::floor(std::log2(static_cast<float>(std::max(width, height)))));
}

}  // namespace

GpuScene::GpuScene(const Scene& scene, float maxAnisotropy) : maxAnisotropy_(maxAnisotropy) {
  for (const Mesh& mesh : scene.meshes) {
    auto& gpuMesh = meshes_.emplace_back();
    for (const auto* list : {&mesh.primitives, &mesh.linesAndPoints}) {
      for (const Primitive& primitive : *list) uploadPrimitive(primitive, gpuMesh.emplace_back());
    }
  }
  for (const MeshInstance& instance : scene.instances) {
    if (instance.mesh < 0 || static_cast<size_t>(instance.mesh) >= meshes_.size()) continue;
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    auto& gpuMesh = meshes_[static_cast<size_t>(instance.mesh)];
    // gpuMesh holds mesh.primitives, then mesh.linesAndPoints, in order.
    for (size_t p = 0; p < gpuMesh.size(); ++p) {
      if (gpuMesh[p].indexCount == 0) continue;
      const bool triangles = p < mesh.primitives.size();
      const Primitive& primitive =
          triangles ? mesh.primitives[p] : mesh.linesAndPoints[p - mesh.primitives.size()];
      drawItems_.push_back({gpuMesh[p].vertexArray.id(), gpuMesh[p].indexCount, primitive.material,
                            instance.world, primitive.topology, primitive.unlit});
    }
  }
  uploadTextures(scene);
}

void GpuScene::uploadPrimitive(const Primitive& primitive, GpuPrimitive& gpu) {
  const auto vertexBytes = static_cast<GLsizeiptr>(primitive.vertices.size() * sizeof(Vertex));
  const auto indexBytes = static_cast<GLsizeiptr>(primitive.indices.size() * sizeof(std::uint32_t));
  glNamedBufferStorage(gpu.vertices.id(), std::max<GLsizeiptr>(vertexBytes, 1),
                       primitive.vertices.data(), 0);
  glNamedBufferStorage(gpu.indices.id(), std::max<GLsizeiptr>(indexBytes, 1),
                       primitive.indices.data(), 0);
  gpuBytes_ += static_cast<std::size_t>(vertexBytes + indexBytes);
  gpu.indexCount = static_cast<GLsizei>(primitive.indices.size());
  const GLuint vao = gpu.vertexArray.id();
  glVertexArrayVertexBuffer(vao, 0, gpu.vertices.id(), 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vao, gpu.indices.id());
  setAttribute(vao, 0, 3, offsetof(Vertex, position));
  setAttribute(vao, 1, 3, offsetof(Vertex, normal));
  setAttribute(vao, 2, 4, offsetof(Vertex, tangent));
  setAttribute(vao, 3, 2, offsetof(Vertex, uv0));
  setAttribute(vao, 4, 2, offsetof(Vertex, uv1));
  setAttribute(vao, 5, 4, offsetof(Vertex, color));
}

void GpuScene::uploadTextures(const Scene& scene) {
  textures_.resize(scene.images.size());
  auto upload = [&](const TextureRef& ref, bool srgb) {
    if (!ref.valid() || static_cast<size_t>(ref.image) >= scene.images.size()) return;
    auto key = std::make_pair(ref.image, srgb);
    gl::Texture& texture = textures_[static_cast<size_t>(ref.image)][srgb ? 1 : 0];
    if (texture.id() == 0) {
      const Image8& image = scene.images[static_cast<size_t>(ref.image)];
      if (image.width <= 0 || image.height <= 0 || image.channels != 4) return;
      texture = gl::Texture(GL_TEXTURE_2D);
      const int levels = mipLevels(image.width, image.height);
      glTextureStorage2D(texture.id(), levels, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, image.width,
                         image.height);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTextureSubImage2D(texture.id(), 0, 0, 0, image.width, image.height, GL_RGBA,
                          GL_UNSIGNED_BYTE, image.pixels.data());
      glGenerateTextureMipmap(texture.id());
      gpuBytes_ += static_cast<std::size_t>(image.width) * image.height * 4 * 4 / 3;
    }
    bindings_[key] = {texture.id(), samplerFor(ref.sampler)};
  };
  for (const Material& material : scene.materials) {
    for (const MaterialTextureSlot& slot : materialTextureSlots(material)) {
      upload(*slot.texture, slot.srgb);
    }
  }
}

GLuint GpuScene::samplerFor(const Sampler& sampler) {
  auto key = std::make_tuple(sampler.magFilter, sampler.minFilter, sampler.wrapS, sampler.wrapT);
  auto it = samplers_.find(key);
  if (it != samplers_.end()) return it->second.id();
  gl::SamplerObject object;
  const GLuint id = object.id();
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER,
                      sampler.magFilter == GL_NEAREST ? GL_NEAREST : GL_LINEAR);
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, sampler.minFilter);
  glSamplerParameteri(id, GL_TEXTURE_WRAP_S, sampler.wrapS);
  glSamplerParameteri(id, GL_TEXTURE_WRAP_T, sampler.wrapT);
  if (usesMipmaps(sampler.minFilter) && maxAnisotropy_ > 1.0F) {
    glSamplerParameterf(id, GL_TEXTURE_MAX_ANISOTROPY, maxAnisotropy_);
  }
  return samplers_.emplace(key, std::move(object)).first->second.id();
}

GpuScene::BoundTexture GpuScene::texture(const TextureRef& ref, bool srgb) const {
  auto it = bindings_.find({ref.image, srgb});
  return it == bindings_.end() ? BoundTexture{} : it->second;
}

}  // namespace lgh
