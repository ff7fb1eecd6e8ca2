#include "gl/uniform_locations.hpp"

namespace lgh::gl {

GLint UniformLocations::operator[](std::string_view name) {
  if (const auto it = locations_.find(name); it != locations_.end()) return it->second;
  const std::string key(name);
  const GLint location = glGetUniformLocation(program_, key.c_str());
  locations_.emplace(key, location);
  return location;
}

}  // namespace lgh::gl
