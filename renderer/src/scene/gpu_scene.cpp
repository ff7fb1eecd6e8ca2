#include "scene/gpu_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <fmt/format.h>
#include <glm/gtc/matrix_inverse.hpp>

namespace lgh {
namespace {

constexpr GLuint kVertexBinding = 0;
constexpr GLuint kDrawTransformBinding = 1;

void setAttribute(GLuint vao, GLuint location, GLint size, GLuint offset,
                  GLuint binding = kVertexBinding) {
  glEnableVertexArrayAttrib(vao, location);
  glVertexArrayAttribFormat(vao, location, size, GL_FLOAT, GL_FALSE, offset);
  glVertexArrayAttribBinding(vao, location, binding);
}

// One draw item's transforms as the vertex array reads them (GpuScene::kDrawTransformLocation).
struct DrawTransform {
  glm::mat4 world;
  std::array<glm::vec4, 3> normal;  // the normal matrix's columns, each padded to 16 bytes
};

bool usesMipmaps(int minFilter) {
  return minFilter == GL_NEAREST_MIPMAP_NEAREST || minFilter == GL_LINEAR_MIPMAP_NEAREST ||
         minFilter == GL_NEAREST_MIPMAP_LINEAR || minFilter == GL_LINEAR_MIPMAP_LINEAR;
}

}  // namespace

glm::vec3 GpuScene::centreOf(const DrawItem& item) {
  Bounds bounds;
  if (item.primitive != nullptr) {
    for (const Vertex& vertex : item.primitive->vertices) bounds.extend(vertex.position);
  }
  if (bounds.empty()) return glm::vec3(item.world[3]);
  return glm::vec3(item.world * glm::vec4(bounds.center(), 1.0F));
}

GpuScene::GpuScene(const Scene& scene, const GpuSceneOptions& options, const StagedScene* staged,
                   const SceneMipChains* mipChains)
    : GpuScene(scene, options, VertexArraysLater{}, staged, mipChains) {
  makeVertexArrays();
}

GpuScene::GpuScene(const Scene& scene, const GpuSceneOptions& options, VertexArraysLater /*later*/,
                   const StagedScene* staged, const SceneMipChains* mipChains)
    : aheadMipChains_(mipChains),
      scene_(scene),
      options_(options),
      capabilities_(options.capabilities ? *options.capabilities : TextureCapabilities::query()) {
  const GeometryLayout layout = geometryLayout(scene);
  uploadGeometry(scene, layout, staged);
  for (const MeshInstance& instance : scene.instances) {
    if (instance.mesh < 0 || static_cast<size_t>(instance.mesh) >= scene.meshes.size()) continue;
    forEachPrimitive(scene, layout, static_cast<size_t>(instance.mesh),
                     [&](const Primitive& primitive, const PrimitiveRange& range) {
                       if (range.indexCount == 0) return;
                       const auto drawIndex = static_cast<GLuint>(drawItems_.size());
                       const bool mirrored = glm::determinant(glm::mat3(instance.world)) < 0.0F;
                       drawItems_.push_back({0, range.indexCount, range.firstIndex,
                                             range.baseVertex, primitive.material, instance.world,
                                             primitive.topology, primitive.unlit,
                                             primitive.tangents, &primitive, drawIndex, mirrored});
                     });
  }
  uploadDrawTransforms();
  // The materials' own textures now, so that a scene's first frame and its load time carry them.
  for (const Material& material : scene.materials) {
    for (const MaterialTextureSlot& slot : materialTextureSlots(material)) {
      texture(*slot.texture, slot.usage, staged);
    }
  }
  // The chains belong to the caller and end with it; a texture uploaded later (one a frame's
  // material overrides sample) builds its own levels.
  aheadMipChains_ = nullptr;
}

GpuScene::~GpuScene() = default;

std::unique_ptr<GpuScene> GpuScene::uploadShared(const Scene& scene,
                                                 const GpuSceneOptions& options) {
  std::unique_ptr<GpuScene> gpu(new GpuScene(scene, options, VertexArraysLater{}));
  gpu->uploaded_ = gl::Fence::insert();
  return gpu;
}

void GpuScene::adopt() {
  if (vertexArrays_) return;
  uploaded_.queueWait();
  uploaded_ = gl::Fence();
  makeVertexArrays();
}

void GpuScene::makeVertexArrays() {
  vertexArray_ = gl::VertexArray();
  const GLuint vao = vertexArray_.id();
  glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vao, indices_.id());
  setAttribute(vao, 0, 3, offsetof(Vertex, position));
  setAttribute(vao, 1, 3, offsetof(Vertex, normal));
  setAttribute(vao, 2, 4, offsetof(Vertex, tangent));
  setAttribute(vao, 3, 2, offsetof(Vertex, uv0));
  setAttribute(vao, 4, 2, offsetof(Vertex, uv1));
  setAttribute(vao, 5, 4, offsetof(Vertex, color));
  glVertexArrayVertexBuffer(vao, kDrawTransformBinding, drawTransforms_.id(), 0,
                            sizeof(DrawTransform));
  glVertexArrayBindingDivisor(vao, kDrawTransformBinding, 1);
  for (GLuint column = 0; column < 4; ++column) {
    setAttribute(vao, kDrawTransformLocation + column, 4,
                 offsetof(DrawTransform, world) + column * sizeof(glm::vec4),
                 kDrawTransformBinding);
  }
  for (GLuint column = 0; column < 3; ++column) {
    setAttribute(vao, kDrawTransformLocation + 4 + column, 3,
                 offsetof(DrawTransform, normal) + column * sizeof(glm::vec4),
                 kDrawTransformBinding);
  }
  for (DrawItem& item : drawItems_) item.vertexArray = vao;
  vertexArrays_ = true;
}

void GpuScene::releaseVertexArrays() {
  vertexArray_.reset();
  for (DrawItem& item : drawItems_) item.vertexArray = 0;
  vertexArrays_ = false;
}

void GpuScene::uploadGeometry(const Scene& scene, const GeometryLayout& layout,
                              const StagedScene* staged) {
  const auto vertexBytes = static_cast<GLsizeiptr>(layout.vertexBytes());
  const auto indexBytes = static_cast<GLsizeiptr>(layout.indexBytes());
  vertices_ = takeBuffer(vertexBytes);
  indices_ = takeBuffer(indexBytes);
  geometryBytes_ = static_cast<std::size_t>(vertexBytes + indexBytes);
  if (staged != nullptr) {
    // Laid out there as here (scene/geometry_layout.hpp): one copy each.
    if (vertexBytes > 0) {
      glCopyNamedBufferSubData(staged->buffer, vertices_.id(), staged->vertices, 0, vertexBytes);
    }
    if (indexBytes > 0) {
      glCopyNamedBufferSubData(staged->buffer, indices_.id(), staged->indices, 0, indexBytes);
    }
    return;
  }
  for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
    forEachPrimitive(
        scene, layout, mesh, [&](const Primitive& primitive, const PrimitiveRange& at) {
          if (!primitive.vertices.empty()) {
            glNamedBufferSubData(
                vertices_.id(),
                static_cast<GLintptr>(static_cast<std::size_t>(at.baseVertex) * sizeof(Vertex)),
                static_cast<GLsizeiptr>(primitive.vertices.size() * sizeof(Vertex)),
                primitive.vertices.data());
          }
          if (!primitive.indices.empty()) {
            glNamedBufferSubData(
                indices_.id(), static_cast<GLintptr>(at.firstIndex * sizeof(std::uint32_t)),
                static_cast<GLsizeiptr>(primitive.indices.size() * sizeof(std::uint32_t)),
                primitive.indices.data());
          }
        });
  }
}

void GpuScene::uploadDrawTransforms() {
  std::vector<DrawTransform> transforms(std::max<std::size_t>(drawItems_.size(), 1));
  for (std::size_t i = 0; i < drawItems_.size(); ++i) {
    const glm::mat3 normal = glm::inverseTranspose(glm::mat3(drawItems_[i].world));
    transforms[i].world = drawItems_[i].world;
    for (int column = 0; column < 3; ++column) {
      transforms[i].normal[static_cast<std::size_t>(column)] = glm::vec4(normal[column], 0.0F);
    }
  }
  const auto bytes = static_cast<GLsizeiptr>(transforms.size() * sizeof(DrawTransform));
  drawTransforms_ = takeBuffer(bytes);
  glNamedBufferSubData(drawTransforms_.id(), 0, bytes, transforms.data());
  geometryBytes_ += static_cast<std::size_t>(bytes);
}

gl::RecycledBuffer GpuScene::takeBuffer(GLsizeiptr bytes) {
  bytes = std::max<GLsizeiptr>(bytes, 1);
  // Without a recycler, and above the largest class kept, a buffer of the exact size.
  gl::RecycledBuffers* from =
      bytes <= kMaxRecycledBufferBytes ? options_.recycledBuffers.get() : nullptr;
  const gl::BufferShape shape =
      from != nullptr ? gl::BufferShape::holding(bytes) : gl::BufferShape{bytes};
  return gl::takeStorage(from, shape, static_cast<std::size_t>(shape.bytes));
}

const GpuScene::UploadedImage* GpuScene::imageTexture(int image, TextureUsage usage,
                                                      const StagedScene* staged) {
  const Image8* rgba8 = scene_.rgba8Image(image);
  if (rgba8 == nullptr) return nullptr;
  const Image8& pixels = *rgba8;
  const auto blocks = scene_.compressedImages.find(image);
  const BlockCompressedImage* precompressed =
      blocks == scene_.compressedImages.end() ? nullptr : &blocks->second;
  // Without compression every linear use shares one RGBA8 texture.
  const bool distinctUses = options_.compression == TextureCompression::Bc;
  const TextureUsage kind =
      distinctUses || usage == TextureUsage::Color ? usage : TextureUsage::Data;
  const auto key = std::make_pair(image, static_cast<int>(kind));
  if (const auto it = textures_.find(key); it != textures_.end()) return &it->second;
  std::optional<StagedPixels> stagedPixels;
  if (staged != nullptr) {
    if (const auto at = staged->images.find(image); at != staged->images.end()) {
      stagedPixels = StagedPixels{staged->buffer, at->second};
    }
  }
  const std::vector<Image8>* mipChain = nullptr;
  if (aheadMipChains_ != nullptr) {
    const auto built = aheadMipChains_->find({image, kind == TextureUsage::Color});
    if (built != aheadMipChains_->end()) mipChain = &built->second;
  }
  UploadedTexture uploaded = uploadTexture(
      pixels, precompressed, kind, options_.compression, capabilities_, warnings_,
      stagedPixels ? &*stagedPixels : nullptr, options_.recycledTextures.get(), mipChain);
  textureBytes_ += uploaded.bytes;
  memory_.bytes += uploaded.bytes;
  memory_.uncompressedBytes += uploaded.uncompressedBytes;
  memory_.textures += 1;
  memory_.compressed += uploaded.compressed ? 1 : 0;
  UploadedImage entry{std::move(uploaded.texture), uploaded.twoChannel};
  return &textures_.emplace(key, std::move(entry)).first->second;
}

GLuint GpuScene::samplerFor(const Sampler& sampler) {
  auto it = samplers_.find(sampler);
  if (it != samplers_.end()) return it->second.id();
  gl::SamplerObject object;
  const GLuint id = object.id();
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER,
                      sampler.magFilter == GL_NEAREST ? GL_NEAREST : GL_LINEAR);
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, sampler.minFilter);
  glSamplerParameteri(id, GL_TEXTURE_WRAP_S, sampler.wrapS);
  glSamplerParameteri(id, GL_TEXTURE_WRAP_T, sampler.wrapT);
  glSamplerParameterfv(id, GL_TEXTURE_BORDER_COLOR, &sampler.borderColor.r);
  // Anisotropy samples the mip levels along the footprint: only with mipmaps. Unset (0): the
  // device's maximum; a request's value is capped at it.
  const float wanted = sampler.anisotropy > 0.0F ? sampler.anisotropy : options_.maxAnisotropy;
  const float anisotropy = std::clamp(wanted, 1.0F, std::max(options_.maxAnisotropy, 1.0F));
  if (sampler.anisotropy > anisotropy) {
    warnings_.push_back(fmt::format("anisotropy {} capped at the device's maximum {}",
                                    sampler.anisotropy, anisotropy));
  }
  if (usesMipmaps(sampler.minFilter) && anisotropy > 1.0F) {
    glSamplerParameterf(id, GL_TEXTURE_MAX_ANISOTROPY, anisotropy);
  }
  return samplers_.emplace(sampler, std::move(object)).first->second.id();
}

GpuScene::BoundTexture GpuScene::texture(const TextureRef& ref, TextureUsage usage) {
  return texture(ref, usage, nullptr);
}

GpuScene::BoundTexture GpuScene::texture(const TextureRef& ref, TextureUsage usage,
                                         const StagedScene* staged) {
  if (!ref.valid()) return {};
  const UploadedImage* image = imageTexture(ref.image, usage, staged);
  if (image == nullptr) return {};
  return {image->texture.id(), samplerFor(ref.sampler), image->twoChannel};
}

std::vector<std::string> GpuScene::takeWarnings() {
  std::vector<std::string> warnings;
  warnings.swap(warnings_);
  return warnings;
}

}  // namespace lgh
