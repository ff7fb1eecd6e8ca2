#include "gl/readback_buffers.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "lgh/error.hpp"

namespace lgh::gl {

// ---- Fence ----

Fence Fence::insert() {
  Fence fence;
  fence.sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  if (fence.sync_ == nullptr) throw Error(ErrorCode::Internal, "glFenceSync returned no fence");
  glFlush();  // so that a wait on another call does not wait for commands never sent
  return fence;
}

Fence::~Fence() {
  if (sync_ != nullptr) glDeleteSync(sync_);
}

Fence::Fence(Fence&& other) noexcept : sync_(std::exchange(other.sync_, nullptr)) {}

Fence& Fence::operator=(Fence&& other) noexcept {
  if (this != &other) {
    if (sync_ != nullptr) glDeleteSync(sync_);
    sync_ = std::exchange(other.sync_, nullptr);
  }
  return *this;
}

bool Fence::wait(std::uint64_t timeoutNs) {
  if (sync_ == nullptr) return true;
  const GLenum status = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, timeoutNs);
  if (status == GL_WAIT_FAILED) {
    throw Error(ErrorCode::Internal, "glClientWaitSync failed: the GL context may be lost");
  }
  return status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED;
}

void Fence::queueWait() const {
  if (sync_ != nullptr) glWaitSync(sync_, 0, GL_TIMEOUT_IGNORED);
}

// ---- The pool ----

struct ReadbackPool::Slot {
  GLuint buffer = 0;
  std::uint8_t* mapped = nullptr;
  std::size_t capacity = 0;
  // Where the bytes are: the mapping, or a heap copy once the pool is gone.
  std::atomic<const std::uint8_t*> bytes{nullptr};
  std::vector<std::uint8_t> detached;
  bool held = false;  // under State::mutex
};

struct ReadbackPool::State {
  mutable std::mutex mutex;
  bool alive = true;
  std::vector<std::shared_ptr<Slot>> returned;
  std::size_t heldBuffers = 0;
  std::size_t heldBytes = 0;
  std::size_t pooledBuffers = 0;
  std::size_t pooledBytes = 0;
};

namespace {

// Free buffers kept for reuse beyond the ones in use.
constexpr std::size_t kMaxFreeBuffers = 4;

class PooledBytes final : public PixelBytes {
 public:
  PooledBytes(std::shared_ptr<ReadbackPool::State> state, std::shared_ptr<ReadbackPool::Slot> slot,
              std::size_t size)
      : state_(std::move(state)), slot_(std::move(slot)), size_(size) {}
  ~PooledBytes() override {
    std::lock_guard lock(state_->mutex);
    slot_->held = false;
    --state_->heldBuffers;
    state_->heldBytes -= slot_->capacity;
    if (state_->alive) state_->returned.push_back(std::move(slot_));
  }
  PooledBytes(const PooledBytes&) = delete;
  PooledBytes& operator=(const PooledBytes&) = delete;

  const std::uint8_t* data() const override { return slot_->bytes.load(); }
  std::size_t size() const override { return size_; }

 private:
  std::shared_ptr<ReadbackPool::State> state_;
  std::shared_ptr<ReadbackPool::Slot> slot_;
  std::size_t size_;
};

constexpr GLbitfield kMapFlags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;

std::shared_ptr<ReadbackPool::Slot> makeSlot(std::size_t bytes) {
  auto slot = std::make_shared<ReadbackPool::Slot>();
  glCreateBuffers(1, &slot->buffer);
  // Client storage: the GPU writes across the bus once, the CPU reads cached memory.
  glNamedBufferStorage(slot->buffer, static_cast<GLsizeiptr>(bytes), nullptr,
                       kMapFlags | GL_CLIENT_STORAGE_BIT);
  void* mapped = glMapNamedBufferRange(slot->buffer, 0, static_cast<GLsizeiptr>(bytes), kMapFlags);
  if (mapped == nullptr) {
    glDeleteBuffers(1, &slot->buffer);
    throw Error(ErrorCode::Internal,
                fmt::format("could not map a read-back buffer of {} bytes (GL error 0x{:x})", bytes,
                            glGetError()));
  }
  slot->mapped = static_cast<std::uint8_t*>(mapped);
  slot->capacity = bytes;
  slot->bytes = slot->mapped;
  return slot;
}

void destroySlot(ReadbackPool::Slot& slot) {
  glUnmapNamedBuffer(slot.buffer);
  glDeleteBuffers(1, &slot.buffer);
  slot.buffer = 0;
  slot.mapped = nullptr;
}

}  // namespace

ReadbackPool::ReadbackPool() : state_(std::make_shared<State>()) {}

ReadbackPool::~ReadbackPool() {
  std::lock_guard lock(state_->mutex);
  state_->alive = false;
  std::size_t detached = 0;
  for (const auto& slot : all_) {
    if (slot->held) {
      slot->detached.assign(slot->mapped, slot->mapped + slot->capacity);
      slot->bytes = slot->detached.data();
      ++detached;
    }
    destroySlot(*slot);
  }
  if (detached > 0) {
    spdlog::warn("renderer: {} frames outlived their renderer; their pixels were copied", detached);
  }
}

void ReadbackPool::reclaimReturned() {
  std::vector<std::shared_ptr<Slot>> returned;
  {
    std::lock_guard lock(state_->mutex);
    returned.swap(state_->returned);
  }
  for (auto& slot : returned) free_.push_back(std::move(slot));
}

void ReadbackPool::trimFree() {
  while (free_.size() > kMaxFreeBuffers) {
    // The smallest goes: large frames are the ones worth keeping a buffer for.
    auto smallest = std::min_element(free_.begin(), free_.end(), [](const auto& a, const auto& b) {
      return a->capacity < b->capacity;
    });
    destroySlot(**smallest);
    {
      std::lock_guard lock(state_->mutex);
      --state_->pooledBuffers;
      state_->pooledBytes -= (*smallest)->capacity;
    }
    std::erase(all_, *smallest);
    free_.erase(smallest);
  }
}

ReadbackPool::Lease ReadbackPool::acquire(std::size_t bytes) {
  reclaimReturned();
  std::shared_ptr<Slot> slot;
  auto fits = free_.end();
  for (auto it = free_.begin(); it != free_.end(); ++it) {
    if ((*it)->capacity >= bytes && (fits == free_.end() || (*it)->capacity < (*fits)->capacity)) {
      fits = it;
    }
  }
  if (fits != free_.end()) {
    slot = std::move(*fits);
    free_.erase(fits);
  } else {
    slot = makeSlot(bytes);
    all_.push_back(slot);
    std::lock_guard lock(state_->mutex);
    ++state_->pooledBuffers;
    state_->pooledBytes += slot->capacity;
  }
  trimFree();
  {
    std::lock_guard lock(state_->mutex);
    slot->held = true;
    ++state_->heldBuffers;
    state_->heldBytes += slot->capacity;
  }
  Lease lease;
  lease.buffer = slot->buffer;
  lease.bytes = std::make_shared<PooledBytes>(state_, std::move(slot), bytes);
  return lease;
}

ReadbackStats ReadbackPool::stats() const {
  std::lock_guard lock(state_->mutex);
  return {state_->heldBuffers, state_->heldBytes, state_->pooledBuffers, state_->pooledBytes};
}

}  // namespace lgh::gl
