#include "scene/gltf/load_context.hpp"

#include <fmt/format.h>

namespace lgh::gltf {

void invalid(const LoadContext& ctx, const std::string& message) {
  throw Error(ErrorCode::Invalid, message, ctx.displayName);
}

void tooLarge(const LoadContext& ctx, const std::string& message) {
  throw Error(ErrorCode::TooLarge, message, ctx.displayName);
}

std::string label(const char* array, int index, const std::string& name) {
  return name.empty() ? fmt::format("/{}/{}", array, index)
                      : fmt::format("/{}/{} ('{}')", array, index, name);
}

}  // namespace lgh::gltf
