#include "request/schema_lookup.hpp"

#include <charconv>
#include <optional>

namespace lgh {
namespace {

using json = nlohmann::json;
using Nodes = std::vector<const json*>;

std::optional<std::size_t> arrayIndex(const std::string& token) {
  std::size_t index = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, index);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return index;
}

const json* child(const json* value, const std::string& token) {
  if (value == nullptr) return nullptr;
  if (value->is_object()) {
    const auto it = value->find(token);
    return it == value->end() ? nullptr : &*it;
  }
  if (value->is_array()) {
    const std::optional<std::size_t> index = arrayIndex(token);
    return index && *index < value->size() ? &(*value)[*index] : nullptr;
  }
  return nullptr;
}

bool hasJsonType(const json& value, const std::string& type) {
  if (type == "object") return value.is_object();
  if (type == "array") return value.is_array();
  if (type == "string") return value.is_string();
  if (type == "boolean") return value.is_boolean();
  if (type == "null") return value.is_null();
  if (type == "integer") return value.is_number_integer();
  if (type == "number") return value.is_number();
  return false;
}

// Evaluates the simple "if" forms the proto schemas use; nullopt for anything else.
std::optional<bool> simpleCondition(const json& condition, const json* value) {
  if (value == nullptr) return std::nullopt;
  if (condition.size() == 1 && condition.contains("type") && condition["type"].is_string()) {
    return hasJsonType(*value, condition["type"].get<std::string>());
  }
  const auto properties = condition.find("properties");
  if (properties != condition.end() && properties->size() == 1 && value->is_object()) {
    const json& schema = properties->begin().value();
    const auto constant = schema.find("const");
    if (constant == schema.end()) return std::nullopt;
    const json* member = child(value, properties->begin().key());
    return member != nullptr && *member == *constant;
  }
  return std::nullopt;
}

class Lookup {
 public:
  explicit Lookup(const json& bundle) : bundle_(bundle) {}

  // `node` after "$ref", plus what its "allOf" and "if"/"then"/"else" add for `value`.
  void expand(const json& schema, const json* value, Nodes& out, int depth = 0) const {
    if (depth > kMaxDepth || !schema.is_object()) return;
    const json* node = &schema;
    const auto ref = node->find("$ref");
    if (ref != node->end() && ref->is_string()) {
      node = resolve(ref->get<std::string>());
      if (node == nullptr) return;
      return expand(*node, value, out, depth + 1);
    }
    out.push_back(node);
    if (const auto all = node->find("allOf"); all != node->end() && all->is_array()) {
      for (const json& part : *all) expand(part, value, out, depth + 1);
    }
    if (const auto condition = node->find("if"); condition != node->end()) {
      const std::optional<bool> holds = simpleCondition(*condition, value);
      if (holds.value_or(true) && node->contains("then")) {
        expand((*node)["then"], value, out, depth + 1);
      }
      if (!holds.value_or(false) && node->contains("else")) {
        expand((*node)["else"], value, out, depth + 1);
      }
    }
  }

  // The nodes that apply to member/element `token` of a value that `parents` apply to.
  Nodes descend(const Nodes& parents, const json* parentValue, const std::string& token,
                const json* value) const {
    Nodes out;
    for (const json* parent : parents) {
      if (const json* schema = memberSchema(*parent, parentValue, token)) {
        expand(*schema, value, out);
      }
    }
    return out;
  }

 private:
  static constexpr int kMaxDepth = 64;  // guards against "$ref" cycles

  const json* resolve(const std::string& ref) const {
    if (!ref.starts_with('#')) return nullptr;
    try {
      return &bundle_.at(json::json_pointer(ref.substr(1)));
    } catch (const json::exception&) {
      return nullptr;
    }
  }

  static const json* memberSchema(const json& parent, const json* parentValue,
                                  const std::string& token) {
    const bool inArray = parentValue != nullptr && parentValue->is_array();
    if (inArray) {
      const auto items = parent.find("items");
      return items != parent.end() && items->is_object() ? &*items : nullptr;
    }
    if (const auto properties = parent.find("properties"); properties != parent.end()) {
      if (const auto it = properties->find(token); it != properties->end()) return &*it;
    }
    const auto additional = parent.find("additionalProperties");
    return additional != parent.end() && additional->is_object() ? &*additional : nullptr;
  }

  const json& bundle_;
};

}  // namespace

const json* valueAt(const json& document, const std::vector<std::string>& tokens) {
  const json* value = &document;
  for (const std::string& token : tokens) value = child(value, token);
  return value;
}

Nodes schemaNodesAt(const json& bundle, const json& document,
                    const std::vector<std::string>& tokens) {
  const Lookup lookup(bundle);
  const json* value = &document;
  Nodes nodes;
  lookup.expand(bundle, value, nodes);
  for (const std::string& token : tokens) {
    const json* next = child(value, token);
    nodes = lookup.descend(nodes, value, token, next);
    value = next;
  }
  return nodes;
}

}  // namespace lgh
