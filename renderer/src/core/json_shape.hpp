// How deeply JSON text nests and how many values it holds, measured in one pass over the bytes
// without parsing or recursion, so that a document past a limit is refused before anything
// expensive or recursive sees it. nlohmann::json's copy and dump, tinygltf's conversion of extras
// and extensions into tinygltf::Value and the schema validators all recurse once per level (a few
// hundred thousand brackets, a few hundred KB of text, overflow a thread's stack), and every
// value costs 16 to 100 bytes once parsed, so that the value count bounds the parse's memory.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace lgh {

struct JsonShapeLimits {
  std::size_t maxDepth = 0;   // arrays and objects inside each other
  std::size_t maxValues = 0;  // an upper bound: 1 + brackets opened + commas, outside strings
};

// Where text first goes past a limit, and which.
struct JsonShapeExcess {
  enum class Limit { Depth, Values };
  Limit limit = Limit::Depth;
  std::size_t offset = 0;  // byte offset of the bracket or comma that went past it

  // "nests deeper than 64 levels of arrays and objects (at byte 123)", for error messages.
  std::string describe(const JsonShapeLimits& limits) const;
};

// Counts brackets and commas outside strings (with their escapes). It does not validate the JSON:
// text that is not JSON is measured as far as brackets go, and the parser that runs next reports
// what else is wrong with it.
std::optional<JsonShapeExcess> findJsonShapeExcess(std::string_view text,
                                                   const JsonShapeLimits& limits);

}  // namespace lgh
