// Asynchronous read-back: pixel-pack buffers mapped once for good (persistent, coherent, in client
// memory) and fences. The GPU copies a frame's output into one of these buffers behind the frame's
// passes; once the frame's fence has signalled, encoders read the pixels through the mapping, on
// any thread, without a copy. The pool lives on the GL thread; buffers come back from any thread
// when the last FramePixels holding them goes, and are reused (docs/ARCHITECTURE.md, "Frames in
// flight").
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "gl/gl_objects.hpp"
#include "lgh/frame_pixels.hpp"

namespace lgh::gl {

// Owns a GLsync.
class Fence {
 public:
  Fence() = default;
  // Inserts a fence behind every command issued so far, and flushes them to the GPU.
  static Fence insert();
  ~Fence();
  Fence(const Fence&) = delete;
  Fence& operator=(const Fence&) = delete;
  Fence(Fence&& other) noexcept;
  Fence& operator=(Fence&& other) noexcept;

  // Whether the GPU got past the fence, waiting up to `timeoutNs` (0: just look). Throws
  // lgh::Error(Internal) when the wait fails (a lost context).
  bool wait(std::uint64_t timeoutNs);
  // Makes the current context's GPU queue wait for the fence (glWaitSync): commands issued after
  // this run after the fenced ones, though those were issued on another context of the share
  // group; the CPU does not wait.
  void queueWait() const;
  bool empty() const { return sync_ == nullptr; }

 private:
  GLsync sync_ = nullptr;
};

struct ReadbackStats {
  std::size_t heldBuffers = 0;  // given out, not yet come back
  std::size_t heldBytes = 0;
  std::size_t pooledBuffers = 0;  // all buffers, free ones included
  std::size_t pooledBytes = 0;
};

class ReadbackPool {
 public:
  ReadbackPool();
  // GL thread. Buffers still held by frames (a FramePixels outliving its renderer) get a copy of
  // their bytes on the heap first, and a warning in the log: read no pixels on another thread
  // while their renderer is destroyed.
  ~ReadbackPool();
  ReadbackPool(const ReadbackPool&) = delete;
  ReadbackPool& operator=(const ReadbackPool&) = delete;

  // A mapped pack buffer of at least `bytes` (GL thread): a free one that fits, or a new one.
  struct Lease {
    GLuint buffer = 0;
    std::shared_ptr<const PixelBytes> bytes;  // the mapping; gives the buffer back when it goes
  };
  Lease acquire(std::size_t bytes);
  // Any thread.
  ReadbackStats stats() const;

  struct Slot;
  struct State;

 private:
  void reclaimReturned();  // GL thread
  void trimFree();         // GL thread

  std::shared_ptr<State> state_;
  std::vector<std::shared_ptr<Slot>> free_;  // GL thread
  std::vector<std::shared_ptr<Slot>> all_;   // GL thread: every buffer that exists
};

}  // namespace lgh::gl
