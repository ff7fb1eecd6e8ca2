// RAII owners for GL objects. Each owns one name, moves but never copies, and deletes it on
// destruction; no naked GLuint escapes a pass.
#pragma once

#include "gl/gl_api.hpp"

#include <utility>

namespace lgh::gl {

template <typename Traits>
class Handle {
 public:
  // Object types created without a target (buffers, framebuffers, ...) are created here; the
  // others (textures, queries, shaders) start empty until given one.
  Handle() {
    if constexpr (requires { Traits::create(); }) id_ = Traits::create();
  }
  explicit Handle(GLenum target) : id_(Traits::create(target)) {}
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
    if (id_ != 0) Traits::destroy(id_);
    id_ = 0;
  }

 private:
  struct EmptyTag {};
  explicit Handle(EmptyTag /*tag*/) {}
  GLuint id_ = 0;
};

struct BufferTraits {
  static GLuint create() {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct TextureTraits {
  static GLuint create(GLenum target) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct FramebufferTraits {
  static GLuint create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct VertexArrayTraits {
  static GLuint create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct SamplerTraits {
  static GLuint create() {
    GLuint id = 0;
    glCreateSamplers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteSamplers(1, &id); }
};
struct QueryTraits {
  static GLuint create(GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};
struct ProgramTraits {
  static GLuint create() { return glCreateProgram(); }
  static void destroy(GLuint id) { glDeleteProgram(id); }
};
struct ShaderTraits {
  static GLuint create(GLenum stage) { return glCreateShader(stage); }
  static void destroy(GLuint id) { glDeleteShader(id); }
};

// GL_EXT_memory_object / GL_EXT_semaphore: memory and semaphores imported from Vulkan.
struct MemoryObjectTraits {
  static GLuint create() {
    GLuint id = 0;
    glCreateMemoryObjectsEXT(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteMemoryObjectsEXT(1, &id); }
};
struct SemaphoreTraits {
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
