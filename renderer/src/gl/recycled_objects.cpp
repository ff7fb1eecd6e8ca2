#include "gl/recycled_objects.hpp"

namespace lgh::gl {

Texture makeStorage(const TextureShape& shape) {
  Texture texture(GL_TEXTURE_2D);
  glTextureStorage2D(texture.id(), shape.levels, shape.format, shape.width, shape.height);
  return texture;
}

Buffer makeStorage(const BufferShape& shape) {
  Buffer buffer;
  glNamedBufferStorage(buffer.id(), shape.bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
  return buffer;
}

}  // namespace lgh::gl
