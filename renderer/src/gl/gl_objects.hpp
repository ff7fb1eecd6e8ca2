// RAII owners for GL objects. Each owns one name, moves but never copies, and deletes it on
// destruction; no naked GLuint escapes a pass. Every live object is counted by kind, so that a
// long-running service can watch for leaks (liveObjects(); lghd's /v1/info and /metrics).
#pragma once

#include "gl/gl_api.hpp"
#include "lgh/enum_names.hpp"

#include <array>
#include <atomic>
#include <cstdint>
#include <utility>

namespace lgh::gl {

enum class ObjectKind {
  Buffer,
  Texture,
  Framebuffer,
  VertexArray,
  Sampler,
  Query,
  Program,
  Shader,
  MemoryObject,
  Semaphore,
  Count
};
inline constexpr std::size_t kObjectKinds = static_cast<std::size_t>(ObjectKind::Count);
}  // namespace lgh::gl

template <>
struct lgh::EnumNames<lgh::gl::ObjectKind> {
  static constexpr std::array<EnumName<gl::ObjectKind>, gl::kObjectKinds> names{{
      {"buffer", gl::ObjectKind::Buffer},
      {"texture", gl::ObjectKind::Texture},
      {"framebuffer", gl::ObjectKind::Framebuffer},
      {"vertex_array", gl::ObjectKind::VertexArray},
      {"sampler", gl::ObjectKind::Sampler},
      {"query", gl::ObjectKind::Query},
      {"program", gl::ObjectKind::Program},
      {"shader", gl::ObjectKind::Shader},
      {"memory_object", gl::ObjectKind::MemoryObject},
      {"semaphore", gl::ObjectKind::Semaphore},
  }};
};

namespace lgh::gl {

namespace detail {
extern std::array<std::atomic<std::int64_t>, kObjectKinds> gLiveObjects;
inline void countObject(ObjectKind kind, std::int64_t delta) {
  gLiveObjects[static_cast<std::size_t>(kind)].fetch_add(delta, std::memory_order_relaxed);
}
}  // namespace detail

// Live GL objects of every context of the process, by kind (names: EnumNames<ObjectKind>).
std::array<std::int64_t, kObjectKinds> liveObjects();

template <typename Traits>
class Handle {
 public:
  // Object types created without a target (buffers, framebuffers, ...) are created here; the
  // others (textures, queries, shaders) start empty until given one.
  Handle() {
    if constexpr (requires { Traits::create(); }) adopt(Traits::create());
  }
  explicit Handle(GLenum target) { adopt(Traits::create(target)); }
  // A handle with no object yet (for objects of extensions that may be missing).
  static Handle empty() { return Handle(EmptyTag{}); }
  ~Handle() { reset(); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  GLuint id() const { return id_; }
  void reset() {
    if (id_ != 0) {
      Traits::destroy(id_);
      detail::countObject(Traits::kKind, -1);
    }
    id_ = 0;
  }

 private:
  void adopt(GLuint id) {
    id_ = id;
    if (id_ != 0) detail::countObject(Traits::kKind, 1);
  }

  struct EmptyTag {};
  explicit Handle(EmptyTag /*tag*/) {}
  GLuint id_ = 0;
};

struct BufferTraits {
  static constexpr ObjectKind kKind = ObjectKind::Buffer;
  static GLuint create() {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct TextureTraits {
  static constexpr ObjectKind kKind = ObjectKind::Texture;
  static GLuint create(GLenum target) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct FramebufferTraits {
  static constexpr ObjectKind kKind = ObjectKind::Framebuffer;
  static GLuint create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct VertexArrayTraits {
  static constexpr ObjectKind kKind = ObjectKind::VertexArray;
  static GLuint create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct SamplerTraits {
  static constexpr ObjectKind kKind = ObjectKind::Sampler;
  static GLuint create() {
    GLuint id = 0;
    glCreateSamplers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteSamplers(1, &id); }
};
struct QueryTraits {
  static constexpr ObjectKind kKind = ObjectKind::Query;
  static GLuint create(GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};
struct ProgramTraits {
  static constexpr ObjectKind kKind = ObjectKind::Program;
  static GLuint create() { return glCreateProgram(); }
  static void destroy(GLuint id) { glDeleteProgram(id); }
};
struct ShaderTraits {
  static constexpr ObjectKind kKind = ObjectKind::Shader;
  static GLuint create(GLenum stage) { return glCreateShader(stage); }
  static void destroy(GLuint id) { glDeleteShader(id); }
};

// GL_EXT_memory_object / GL_EXT_semaphore: memory and semaphores imported from Vulkan.
struct MemoryObjectTraits {
  static constexpr ObjectKind kKind = ObjectKind::MemoryObject;
  static GLuint create() {
    GLuint id = 0;
    glCreateMemoryObjectsEXT(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteMemoryObjectsEXT(1, &id); }
};
struct SemaphoreTraits {
  static constexpr ObjectKind kKind = ObjectKind::Semaphore;
  static GLuint create() {
    GLuint id = 0;
    glGenSemaphoresEXT(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteSemaphoresEXT(1, &id); }
};

using Buffer = Handle<BufferTraits>;
using Texture = Handle<TextureTraits>;
using Framebuffer = Handle<FramebufferTraits>;
using VertexArray = Handle<VertexArrayTraits>;
using SamplerObject = Handle<SamplerTraits>;
using Query = Handle<QueryTraits>;
using Program = Handle<ProgramTraits>;
using Shader = Handle<ShaderTraits>;
using MemoryObject = Handle<MemoryObjectTraits>;
using Semaphore = Handle<SemaphoreTraits>;

// A buffer with storage of a known size (immutable storage, dynamic updates allowed).
struct SizedBuffer {
  Buffer buffer;
  GLsizeiptr size = 0;

  // Grows (reallocates) to at least `bytes`; contents are not kept.
  void reserve(GLsizeiptr bytes, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT) {
    if (bytes <= size && buffer.id() != 0) return;
    buffer = Buffer();
    glNamedBufferStorage(buffer.id(), bytes > 0 ? bytes : 16, nullptr, flags);
    size = bytes;
  }
  GLuint id() const { return buffer.id(); }
};

}  // namespace lgh::gl
