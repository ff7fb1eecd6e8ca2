// GL storage kept across scenes. A freed scene's textures and geometry buffers come back to a
// Recycler, and a later object of the same shape takes one instead of storage of its own; its
// contents are written anew (a texture's level 0 and mip levels, a buffer's used bytes), so
// nothing of the old scene shows. With the scene cache off every thumbnail made and deleted its
// objects, and on NVIDIA's driver both were render-thread time (docs/BENCHMARKS.md, "GPU targets,
// eleventh round").
//
// At most the bytes given to create() wait in a recycler; beyond that the objects kept longest
// are deleted. GL orders an object's new upload after the draws that read its old contents, so an
// object may be taken again while earlier frames are still in flight. Objects are deleted by the
// thread that gives them back or destroys the recycler: a thread with the render context (or one
// of its share group) current.
#pragma once

#include <algorithm>
#include <bit>
#include <compare>
#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

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

// A buffer's storage: a power-of-two size class (GL_DYNAMIC_STORAGE_BIT, for glNamedBufferSubData
// and copies into it).
struct BufferShape {
  GLsizeiptr bytes = 0;
  auto operator<=>(const BufferShape&) const = default;
  static constexpr GLsizeiptr kMinBytes = GLsizeiptr{4} << 10;
  // The class of a buffer of at least `bytes` usable bytes.
  static BufferShape holding(GLsizeiptr bytes) {
    return {static_cast<GLsizeiptr>(
        std::bit_ceil(static_cast<std::size_t>(std::max(bytes, kMinBytes))))};
  }
};

Texture makeStorage(const TextureShape& shape);
Buffer makeStorage(const BufferShape& shape);

template <typename Object, typename Shape>
class Recycler;

// An object that goes back to its Recycler when destroyed, or is deleted when it has none (any
// more).
template <typename Object, typename Shape>
class Recycled {
 public:
  Recycled() : object_(Object::empty()) {}
  // An object of its own, deleted as usual.
  explicit Recycled(Object object) : object_(std::move(object)) {}
  ~Recycled() { giveBack(); }
  Recycled(const Recycled&) = delete;
  Recycled& operator=(const Recycled&) = delete;
  Recycled(Recycled&& other) noexcept = default;
  Recycled& operator=(Recycled&& other) noexcept {
    if (this != &other) {
      giveBack();
      object_ = std::move(other.object_);
      shape_ = other.shape_;
      bytes_ = other.bytes_;
      home_ = std::move(other.home_);
    }
    return *this;
  }

  GLuint id() const { return object_.id(); }

 private:
  friend class Recycler<Object, Shape>;
  Recycled(Object object, const Shape& shape, std::size_t bytes,
           std::weak_ptr<Recycler<Object, Shape>> home)
      : object_(std::move(object)), shape_(shape), bytes_(bytes), home_(std::move(home)) {}
  void giveBack() noexcept {
    if (object_.id() == 0) return;
    if (const auto home = home_.lock()) home->giveBack(std::move(object_), shape_, bytes_);
    object_.reset();  // no home (any more): deleted here
  }

  Object object_;
  Shape shape_{};
  std::size_t bytes_ = 0;
  std::weak_ptr<Recycler<Object, Shape>> home_;
};

template <typename Object, typename Shape>
class Recycler : public std::enable_shared_from_this<Recycler<Object, Shape>> {
 public:
  static std::shared_ptr<Recycler> create(std::size_t keptBytes) {
    return std::shared_ptr<Recycler>(new Recycler(keptBytes));
  }
  Recycler(const Recycler&) = delete;
  Recycler& operator=(const Recycler&) = delete;
  ~Recycler() = default;

  // An object with storage of `shape` (`bytes`: what that storage takes): a kept one, or a new
  // one (gl::makeStorage). Its contents are undefined.
  Recycled<Object, Shape> take(const Shape& shape, std::size_t bytes) {
    {
      const std::lock_guard lock(mutex_);
      ++taken_;
      const auto found = std::find_if(kept_.begin(), kept_.end(),
                                      [&](const Kept& kept) { return kept.shape == shape; });
      if (found != kept_.end()) {
        ++recycled_;
        keptBytes_ -= found->bytes;
        Object object = std::move(found->object);
        kept_.erase(found);
        return Recycled<Object, Shape>(std::move(object), shape, bytes, this->weak_from_this());
      }
    }
    return Recycled<Object, Shape>(makeStorage(shape), shape, bytes, this->weak_from_this());
  }

  struct Stats {
    std::size_t taken = 0;     // take() calls
    std::size_t recycled = 0;  // of them, served by a kept object
    std::size_t kept = 0;      // objects waiting here now
    std::size_t keptBytes = 0;
  };
  Stats stats() const {
    const std::lock_guard lock(mutex_);
    return {taken_, recycled_, kept_.size(), keptBytes_};
  }

 private:
  explicit Recycler(std::size_t keptBytes) : limit_(keptBytes) {}
  friend class Recycled<Object, Shape>;
  void giveBack(Object object, const Shape& shape, std::size_t bytes) noexcept {
    std::vector<Object> deleted;  // deleted after the lock is let go
    const std::lock_guard lock(mutex_);
    if (bytes > limit_) {
      deleted.push_back(std::move(object));
      return;
    }
    while (keptBytes_ + bytes > limit_ && !kept_.empty()) {
      keptBytes_ -= kept_.front().bytes;
      deleted.push_back(std::move(kept_.front().object));
      kept_.pop_front();
    }
    keptBytes_ += bytes;
    kept_.push_back({std::move(object), shape, bytes});
  }

  struct Kept {
    Object object;
    Shape shape;
    std::size_t bytes = 0;
  };
  std::size_t limit_;
  mutable std::mutex mutex_;
  std::deque<Kept> kept_;  // oldest first
  std::size_t keptBytes_ = 0;
  std::size_t taken_ = 0;
  std::size_t recycled_ = 0;
};

// Storage of `shape` from `from` (`bytes`: what it takes), or of its own when there is no
// recycler.
template <typename Object, typename Shape>
Recycled<Object, Shape> takeStorage(Recycler<Object, Shape>* from, const Shape& shape,
                                    std::size_t bytes) {
  return from != nullptr ? from->take(shape, bytes) : Recycled<Object, Shape>(makeStorage(shape));
}

using RecycledTexture = Recycled<Texture, TextureShape>;
using RecycledTextures = Recycler<Texture, TextureShape>;
using RecycledBuffer = Recycled<Buffer, BufferShape>;
using RecycledBuffers = Recycler<Buffer, BufferShape>;

}  // namespace lgh::gl
