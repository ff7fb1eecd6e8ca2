#include "core/json_shape.hpp"

#include <fmt/format.h>

namespace lgh {

std::string JsonShapeExcess::describe(const JsonShapeLimits& limits) const {
  if (limit == Limit::Depth) {
    return fmt::format(
        "nests deeper than the limit of {} levels of arrays and objects (at byte {})",
        limits.maxDepth, offset);
  }
  return fmt::format("holds more than the limit of {} values (at byte {})", limits.maxValues,
                     offset);
}

std::optional<JsonShapeExcess> findJsonShapeExcess(std::string_view text,
                                                   const JsonShapeLimits& limits) {
  using Limit = JsonShapeExcess::Limit;
  std::size_t depth = 0;
  std::size_t values = 1;
  bool inString = false;
  bool escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        inString = false;
      }
      continue;
    }
    switch (c) {
      case '"':
        inString = true;
        break;
      case '[':
      case '{':
        if (++depth > limits.maxDepth) return JsonShapeExcess{Limit::Depth, i};
        if (++values > limits.maxValues) return JsonShapeExcess{Limit::Values, i};
        break;
      case ',':
        if (++values > limits.maxValues) return JsonShapeExcess{Limit::Values, i};
        break;
      case ']':
      case '}':
        // Unbalanced closers are the parser's to report; they must not hide later depth.
        if (depth > 0) --depth;
        break;
      default:
        break;
    }
  }
  return std::nullopt;
}

}  // namespace lgh
