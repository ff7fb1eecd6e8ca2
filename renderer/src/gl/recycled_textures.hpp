// Texture storage kept across scenes. A freed scene's RGBA8 textures come back here, and a later
// texture of the same format, size and level count takes one instead of storage of its own: its
// level 0 and mip levels are written anew, so nothing of the old image shows. With the scene
// cache off every thumbnail made and deleted its textures, and on NVIDIA's driver both were
// render-thread time (docs/BENCHMARKS.md, "GPU targets, eleventh round").
//
// At most the bytes given to create() wait here; beyond that the textures kept longest are deleted.
// GL orders a texture's new upload after the draws that sampled its old image, so a texture may
// be taken again while earlier frames are still in flight. Textures are deleted by the thread
// that gives them back or destroys this: a thread with the render context (or one of its share
// group) current.
#pragma once

#include <compare>
#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>

#include "gl/gl_objects.hpp"

namespace lgh::gl {

// The immutable storage of a 2D texture (glTextureStorage2D's arguments).
struct TextureShape {
  GLenum format = GL_NONE;
  GLsizei width = 0;
  GLsizei height = 0;
  GLsizei levels = 0;
  auto operator<=>(const TextureShape&) const = default;
};

class RecycledTextures;

// A texture that goes back to its RecycledTextures when destroyed, or is deleted when it has
// none (any more).
class RecycledTexture {
 public:
  RecycledTexture() : texture_(Texture::empty()) {}
  // A texture of its own, deleted as usual.
  explicit RecycledTexture(Texture texture) : texture_(std::move(texture)) {}
  ~RecycledTexture() { giveBack(); }
  RecycledTexture(const RecycledTexture&) = delete;
  RecycledTexture& operator=(const RecycledTexture&) = delete;
  RecycledTexture(RecycledTexture&& other) noexcept = default;
  RecycledTexture& operator=(RecycledTexture&& other) noexcept;

  GLuint id() const { return texture_.id(); }

 private:
  friend class RecycledTextures;
  RecycledTexture(Texture texture, const TextureShape& shape, std::size_t bytes,
                  std::weak_ptr<RecycledTextures> home)
      : texture_(std::move(texture)), shape_(shape), bytes_(bytes), home_(std::move(home)) {}
  void giveBack() noexcept;

  Texture texture_;
  TextureShape shape_;
  std::size_t bytes_ = 0;
  std::weak_ptr<RecycledTextures> home_;
};

class RecycledTextures : public std::enable_shared_from_this<RecycledTextures> {
 public:
  static std::shared_ptr<RecycledTextures> create(std::size_t keptBytes);
  RecycledTextures(const RecycledTextures&) = delete;
  RecycledTextures& operator=(const RecycledTextures&) = delete;
  ~RecycledTextures() = default;

  // A GL_TEXTURE_2D with storage of `shape` (`bytes`: what its levels take): a kept one, or a
  // new one. Its levels' contents are undefined.
  RecycledTexture take(const TextureShape& shape, std::size_t bytes);

  struct Stats {
    std::size_t taken = 0;     // take() calls
    std::size_t recycled = 0;  // of them, served by a kept texture
    std::size_t kept = 0;      // textures waiting here now
    std::size_t keptBytes = 0;
  };
  Stats stats() const;

 private:
  explicit RecycledTextures(std::size_t keptBytes) : limit_(keptBytes) {}
  friend class RecycledTexture;
  void giveBack(Texture texture, const TextureShape& shape, std::size_t bytes) noexcept;

  struct Kept {
    Texture texture;
    TextureShape shape;
    std::size_t bytes = 0;
  };
  std::size_t limit_;
  mutable std::mutex mutex_;
  std::deque<Kept> kept_;  // oldest first
  std::size_t keptBytes_ = 0;
  std::size_t taken_ = 0;
  std::size_t recycled_ = 0;
};

}  // namespace lgh::gl
