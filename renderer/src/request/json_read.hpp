// Reading validated JSON into the request's structs. The schema has checked types and ranges:
// these only copy what is present, leaving the struct's default (or an empty optional) for what
// is not. Shared by the request parser and the material parameters.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "lgh/enum_names.hpp"

namespace lgh::json_read {

template <typename T>
void read(const nlohmann::json& object, const char* key, T& out) {
  if (const auto it = object.find(key); it != object.end()) out = it->get<T>();
}

template <typename T>
void read(const nlohmann::json& object, const char* key, std::optional<T>& out) {
  if (const auto it = object.find(key); it != object.end()) out = it->get<T>();
}

// The enum named at `key`, if present. The schema's enum lists and the EnumNames tables agree
// (tests/unit/test_request.cpp).
template <typename Enum>
std::optional<Enum> enumAt(const nlohmann::json& object, const char* key) {
  const auto it = object.find(key);
  if (it == object.end()) return std::nullopt;
  return enumFromName<Enum>(it->get_ref<const std::string&>());
}

template <typename Enum>
void readEnum(const nlohmann::json& object, const char* key, Enum& out) {
  if (const std::optional<Enum> value = enumAt<Enum>(object, key)) out = *value;
}

template <typename Enum>
void readEnum(const nlohmann::json& object, const char* key, std::optional<Enum>& out) {
  if (const std::optional<Enum> value = enumAt<Enum>(object, key)) out = value;
}

}  // namespace lgh::json_read
