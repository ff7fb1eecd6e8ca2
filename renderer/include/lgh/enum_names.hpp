// One table of names per enum, kept next to the enum it names (request.hpp, renderer_options.hpp):
// the request parser, the daemon's answers, the CLI's choices and the logs all read the same one.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace lgh {

template <typename Enum>
struct EnumName {
  std::string_view name;
  Enum value;
};

// Specialized next to each enum with `static constexpr std::array<EnumName<Enum>, N> names`.
// The first entry of a value is its canonical name; later ones are accepted aliases.
template <typename Enum>
struct EnumNames;

template <typename Enum>
constexpr std::string_view enumName(Enum value) {
  for (const auto& entry : EnumNames<Enum>::names) {
    if (entry.value == value) return entry.name;
  }
  return "?";
}

template <typename Enum>
constexpr std::optional<Enum> enumFromName(std::string_view name) {
  for (const auto& entry : EnumNames<Enum>::names) {
    if (entry.name == name) return entry.value;
  }
  return std::nullopt;
}

// Every accepted name, "a, b, c": for error messages and --help.
template <typename Enum>
std::string enumNameList() {
  std::string list;
  for (const auto& entry : EnumNames<Enum>::names) {
    if (!list.empty()) list += ", ";
    list += entry.name;
  }
  return list;
}

}  // namespace lgh
