#include "gl/recycled_textures.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace lgh::gl {

RecycledTexture& RecycledTexture::operator=(RecycledTexture&& other) noexcept {
  if (this != &other) {
    giveBack();
    texture_ = std::move(other.texture_);
    shape_ = other.shape_;
    bytes_ = other.bytes_;
    home_ = std::move(other.home_);
  }
  return *this;
}

void RecycledTexture::giveBack() noexcept {
  if (texture_.id() == 0) return;
  if (const auto home = home_.lock()) {
    home->giveBack(std::move(texture_), shape_, bytes_);
  }
  texture_.reset();  // no home (any more): deleted here
}

std::shared_ptr<RecycledTextures> RecycledTextures::create(std::size_t keptBytes) {
  return std::shared_ptr<RecycledTextures>(new RecycledTextures(keptBytes));
}

RecycledTexture RecycledTextures::take(const TextureShape& shape, std::size_t bytes) {
  {
    const std::lock_guard lock(mutex_);
    ++taken_;
    const auto found = std::find_if(kept_.begin(), kept_.end(),
                                    [&](const Kept& kept) { return kept.shape == shape; });
    if (found != kept_.end()) {
      ++recycled_;
      keptBytes_ -= found->bytes;
      Texture texture = std::move(found->texture);
      kept_.erase(found);
      return RecycledTexture(std::move(texture), shape, bytes, weak_from_this());
    }
  }
  Texture texture(GL_TEXTURE_2D);
  glTextureStorage2D(texture.id(), shape.levels, shape.format, shape.width, shape.height);
  return RecycledTexture(std::move(texture), shape, bytes, weak_from_this());
}

void RecycledTextures::giveBack(Texture texture, const TextureShape& shape,
                                std::size_t bytes) noexcept {
  std::vector<Texture> deleted;  // deleted after the lock
  {
    const std::lock_guard lock(mutex_);
    if (bytes > limit_) {
      deleted.push_back(std::move(texture));
    } else {
      while (keptBytes_ + bytes > limit_ && !kept_.empty()) {
        keptBytes_ -= kept_.front().bytes;
        deleted.push_back(std::move(kept_.front().texture));
        kept_.pop_front();
      }
      keptBytes_ += bytes;
      kept_.push_back({std::move(texture), shape, bytes});
    }
  }
}

RecycledTextures::Stats RecycledTextures::stats() const {
  const std::lock_guard lock(mutex_);
  return {taken_, recycled_, kept_.size(), keptBytes_};
}

}  // namespace lgh::gl
