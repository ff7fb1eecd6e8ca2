#include "gl/staging_memory.hpp"

#include <algorithm>
#include <iterator>
#include <utility>

#include "lgh/error.hpp"

namespace lgh::gl {
namespace {

std::size_t aligned(std::size_t bytes) {
  return (bytes + StagingMemory::kAlignment - 1) / StagingMemory::kAlignment *
         StagingMemory::kAlignment;
}

}  // namespace

StagingMemory::StagingMemory(std::size_t bytes) : capacity_(aligned(bytes)) {
  constexpr GLbitfield kFlags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  glNamedBufferStorage(buffer_.id(), static_cast<GLsizeiptr>(capacity_), nullptr, kFlags);
  mapped_ = static_cast<std::byte*>(
      glMapNamedBufferRange(buffer_.id(), 0, static_cast<GLsizeiptr>(capacity_), kFlags));
  if (mapped_ == nullptr) {
    throw Error(ErrorCode::Internal,
                "the driver could not map the upload staging memory persistently",
                "upload staging");
  }
  free_.emplace(0, capacity_);
}

StagingMemory::~StagingMemory() {
  // Every region is back or retired: the scene cache frees its prefetches first. The buffer is
  // unmapped when it is deleted.
  retired_.clear();
}

std::optional<StagingMemory::Region> StagingMemory::reserve(std::size_t bytes) {
  const std::size_t size = aligned(std::max<std::size_t>(bytes, 1));
  const std::lock_guard lock(mutex_);
  for (auto it = free_.begin(); it != free_.end(); ++it) {
    if (it->second < size) continue;
    const GLintptr offset = it->first;
    const std::size_t left = it->second - size;
    free_.erase(it);
    if (left > 0) free_.emplace(offset + static_cast<GLintptr>(size), left);
    inUse_ += size;
    return Region(this, offset, size, mapped_ + offset);
  }
  return std::nullopt;
}

void StagingMemory::retire(Region region) {
  if (region.empty()) return;
  retired_.push_back({Fence::insert(), region.offset_, region.size_});
  region.owner_ = nullptr;  // freed by reclaim(), not by the region
}

void StagingMemory::reclaim() {
  while (!retired_.empty() && retired_.front().fence.wait(0)) {
    release(retired_.front().offset, retired_.front().size);
    retired_.pop_front();
  }
}

std::size_t StagingMemory::bytesInUse() const {
  const std::lock_guard lock(mutex_);
  return inUse_;
}

void StagingMemory::release(GLintptr offset, std::size_t size) {
  const std::lock_guard lock(mutex_);
  inUse_ -= size;
  auto next = free_.lower_bound(offset);
  // Merge with the free span before it and the one after it.
  if (next != free_.begin()) {
    auto previous = std::prev(next);
    if (previous->first + static_cast<GLintptr>(previous->second) == offset) {
      offset = previous->first;
      size += previous->second;
      free_.erase(previous);
    }
  }
  if (next != free_.end() && offset + static_cast<GLintptr>(size) == next->first) {
    size += next->second;
    free_.erase(next);
  }
  free_.emplace(offset, size);
}

StagingMemory::Region::Region(Region&& other) noexcept
    : owner_(std::exchange(other.owner_, nullptr)),
      offset_(other.offset_),
      size_(other.size_),
      data_(other.data_) {}

StagingMemory::Region& StagingMemory::Region::operator=(Region&& other) noexcept {
  if (this != &other) {
    reset();
    owner_ = std::exchange(other.owner_, nullptr);
    offset_ = other.offset_;
    size_ = other.size_;
    data_ = other.data_;
  }
  return *this;
}

void StagingMemory::Region::reset() {
  if (owner_ != nullptr) owner_->release(offset_, size_);
  owner_ = nullptr;
}

}  // namespace lgh::gl
