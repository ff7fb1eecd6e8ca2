// Persistently mapped GL memory that any thread may write, for uploads the GL thread then issues
// as GPU copies (glCopyNamedBufferSubData, or glTextureSubImage2D from a pixel-unpack buffer).
// NVIDIA's driver copied client memory on the calling thread at under 2 GB/s, so a 5 MB asset's
// upload was 2.5 ms of the render thread (docs/BENCHMARKS.md, eighth round); written here by a
// prefetch thread, the same bytes cost the render thread one copy command.
//
// Regions are reserved and written on any thread. The GL thread retires a region once it has
// issued the commands that read it; its bytes are reused when a fence behind those commands has
// signalled. A region dropped without being retired (a prefetched scene never drawn) is free at
// once. Made, retired, reclaimed and destroyed on the thread whose context owns the buffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>

#include "gl/gl_objects.hpp"
#include "gl/readback_buffers.hpp"

namespace lgh::gl {

class StagingMemory {
 public:
  explicit StagingMemory(std::size_t bytes);
  ~StagingMemory();
  StagingMemory(const StagingMemory&) = delete;
  StagingMemory& operator=(const StagingMemory&) = delete;

  class Region {
   public:
    Region() = default;
    ~Region() { reset(); }
    Region(Region&& other) noexcept;
    Region& operator=(Region&& other) noexcept;
    Region(const Region&) = delete;
    Region& operator=(const Region&) = delete;

    std::byte* data() const { return data_; }
    GLintptr offset() const { return offset_; }  // in buffer()
    std::size_t size() const { return size_; }
    bool empty() const { return owner_ == nullptr; }
    void reset();  // frees the bytes at once: for a region no GPU command reads

   private:
    friend class StagingMemory;
    Region(StagingMemory* owner, GLintptr offset, std::size_t size, std::byte* data)
        : owner_(owner), offset_(offset), size_(size), data_(data) {}
    StagingMemory* owner_ = nullptr;
    GLintptr offset_ = 0;
    std::size_t size_ = 0;
    std::byte* data_ = nullptr;
  };

  // Any thread: `bytes` of the memory, or nothing when no free span is that large.
  std::optional<Region> reserve(std::size_t bytes);
  // GL thread: the commands issued so far read `region`; its bytes are free once they are done.
  void retire(Region region);
  // GL thread: frees the retired regions whose commands are done (looks, never waits).
  void reclaim();

  GLuint buffer() const { return buffer_.id(); }
  std::size_t capacity() const { return capacity_; }
  std::size_t bytesInUse() const;  // reserved or retired, not yet free

  // Offsets and sizes are multiples of this: any use of a region's start is aligned for it.
  static constexpr std::size_t kAlignment = 256;

 private:
  void release(GLintptr offset, std::size_t size);

  Buffer buffer_;
  std::size_t capacity_ = 0;
  std::byte* mapped_ = nullptr;
  mutable std::mutex mutex_;
  std::map<GLintptr, std::size_t> free_;  // offset -> size, adjacent spans merged
  std::size_t inUse_ = 0;
  struct Retired {
    Fence fence;
    GLintptr offset;
    std::size_t size;
  };
  std::deque<Retired> retired_;  // GL thread only; fences signal in order
};

}  // namespace lgh::gl
