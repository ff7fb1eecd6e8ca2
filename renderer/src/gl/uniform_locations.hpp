// A program's uniform locations, each looked up by name once, and the value last set at each.
// glGetUniformLocation is a string search inside the driver, and the surface passes set about
// forty uniforms for every material they bind: on a scene of many materials that was most of the
// G-buffer pass's issue time. A program keeps its uniforms' values between draws and frames, so a
// value equal to the one set before need not be set again: most materials share most of theirs.
#pragma once

#include <cstddef>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "gl/gl_api.hpp"

namespace lgh::gl {

class UniformLocations {
 public:
  explicit UniformLocations(GLuint program) : program_(program) {}

  GLuint program() const { return program_; }
  // -1 for a name the program does not use (GL ignores a uniform call at -1).
  GLint operator[](std::string_view name) { return slot(name).location; }

  // The location at which to set `value`, or nothing when the program does not use `name` or
  // `value` equals what the last call for `name` was given; records `value` as set. Every value
  // of a uniform that is set through this must be set through this.
  template <typename T>
  std::optional<GLint> changed(std::string_view name, const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    return changedBytes(name, &value, sizeof(T));
  }
  std::optional<GLint> changedBytes(std::string_view name, const void* value, std::size_t size);

 private:
  struct Slot {
    GLint location = -1;
    std::vector<std::byte> last;  // empty until first set
  };
  struct NameHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view name) const {
      return std::hash<std::string_view>{}(name);
    }
  };
  Slot& slot(std::string_view name);

  GLuint program_;
  std::unordered_map<std::string, Slot, NameHash, std::equal_to<>> slots_;
};

}  // namespace lgh::gl
