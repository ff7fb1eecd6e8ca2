#include "scene/staged_scene.hpp"

#include <cstring>
#include <set>

#include "scene/geometry_layout.hpp"

namespace lgh {
namespace {

// The images GpuScene uploads as decoded RGBA8 when it is made: those the materials sample,
// unless they arrived block-compressed or are compressed on upload.
std::set<int> plainImages(const Scene& scene, TextureCompression compression) {
  std::set<int> images;
  if (compression != TextureCompression::None) return images;
  for (const auto& [image, usage] : sampledRgba8Images(scene)) images.insert(image);
  return images;
}

template <typename T>
std::size_t copyAt(std::byte* at, const std::vector<T>& values) {
  if (!values.empty()) std::memcpy(at, values.data(), values.size() * sizeof(T));
  return values.size() * sizeof(T);
}

}  // namespace

std::optional<StagedScene> stageScene(const Scene& scene, gl::StagingMemory& memory,
                                      TextureCompression compression, std::size_t minBytes) {
  const GeometryLayout layout = geometryLayout(scene);
  const std::size_t vertexBytes = layout.vertexBytes();
  const std::size_t indexBytes = layout.indexBytes();
  const std::set<int> images = plainImages(scene, compression);
  constexpr std::size_t kImageAlignment = 16;
  const auto align = [](std::size_t at) {
    return (at + kImageAlignment - 1) / kImageAlignment * kImageAlignment;
  };
  std::size_t total = align(vertexBytes + indexBytes);
  for (const int image : images) {
    total = align(total + scene.images[static_cast<size_t>(image)].pixels.size());
  }
  if (total < minBytes) return std::nullopt;
  std::optional<gl::StagingMemory::Region> region = memory.reserve(total);
  if (!region) return std::nullopt;

  StagedScene staged;
  staged.buffer = memory.buffer();
  staged.vertices = region->offset();
  staged.indices = region->offset() + static_cast<GLintptr>(vertexBytes);
  for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
    forEachPrimitive(
        scene, layout, mesh, [&](const Primitive& primitive, const PrimitiveRange& at) {
          copyAt(region->data() + static_cast<std::size_t>(at.baseVertex) * sizeof(Vertex),
                 primitive.vertices);
          copyAt(region->data() + vertexBytes + at.firstIndex * sizeof(std::uint32_t),
                 primitive.indices);
        });
  }
  std::size_t at = align(vertexBytes + indexBytes);
  for (const int image : images) {
    const auto& pixels = scene.images[static_cast<size_t>(image)].pixels;
    staged.images.emplace(image, region->offset() + static_cast<GLintptr>(at));
    at = align(at + copyAt(region->data() + at, pixels));
  }
  staged.region = std::move(*region);
  return staged;
}

}  // namespace lgh
