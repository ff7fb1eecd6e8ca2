#include "gl/uniform_locations.hpp"

namespace lgh::gl {

UniformLocations::Slot& UniformLocations::slot(std::string_view name) {
  if (const auto it = slots_.find(name); it != slots_.end()) return it->second;
  const std::string key(name);
  Slot entry;
  entry.location = glGetUniformLocation(program_, key.c_str());
  return slots_.emplace(key, std::move(entry)).first->second;
}

std::optional<GLint> UniformLocations::changedBytes(std::string_view name, const void* value,
                                                    std::size_t size) {
  Slot& entry = slot(name);
  if (entry.location < 0) return std::nullopt;
  if (entry.last.size() == size && std::memcmp(entry.last.data(), value, size) == 0) {
    return std::nullopt;
  }
  entry.last.resize(size);
  std::memcpy(entry.last.data(), value, size);
  return entry.location;
}

}  // namespace lgh::gl
