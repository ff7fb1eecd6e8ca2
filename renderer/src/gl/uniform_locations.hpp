// A program's uniform locations, each looked up by name once. glGetUniformLocation is a string
// search inside the driver, and the surface passes set about forty uniforms for every material
// they bind: on a scene of many materials that was most of the G-buffer pass's issue time.
#pragma once

#include <string>
#include <string_view>
#include <unordered_map>

#include "gl/gl_api.hpp"

namespace lgh::gl {

class UniformLocations {
 public:
  explicit UniformLocations(GLuint program) : program_(program) {}

  GLuint program() const { return program_; }
  // -1 for a name the program does not use (GL ignores a uniform call at -1).
  GLint operator[](std::string_view name);

 private:
  struct NameHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view name) const {
      return std::hash<std::string_view>{}(name);
    }
  };
  GLuint program_;
  std::unordered_map<std::string, GLint, NameHash, std::equal_to<>> locations_;
};

}  // namespace lgh::gl
