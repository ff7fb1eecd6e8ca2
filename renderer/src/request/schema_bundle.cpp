#include "request/schema_bundle.hpp"

#include <algorithm>
#include <set>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "lgh/error.hpp"
#include "lgh/request.hpp"
#include "request/embedded_proto.hpp"
#include "request/json_pointer.hpp"

namespace lgh {
namespace {

using json = nlohmann::json;

std::string fileNameOf(std::string_view uri) {
  const std::size_t slash = uri.rfind('/');
  return std::string(slash == std::string_view::npos ? uri : uri.substr(slash + 1));
}

class Bundler {
 public:
  explicit Bundler(std::string rootFile) : rootFile_(std::move(rootFile)) {}

  json run() {
    json root = load(rootFile_);
    rewriteRefs(root, rootFile_);
    lowerDiscriminators(root, rootFile_);
    // Referenced files are appended to pending_ while earlier ones are rewritten.
    for (std::size_t i = 0; i < pending_.size(); ++i) {
      const std::string file = pending_[i];
      json document = load(file);
      document.erase("$schema");
      document.erase("$id");
      rewriteRefs(document, file);
      lowerDiscriminators(document, file);
      root["$defs"][file] = std::move(document);
    }
    return root;
  }

 private:
  static json load(const std::string& file) {
    try {
      return json::parse(protoDocument(file));
    } catch (const json::exception& error) {
      throw Error(ErrorCode::Internal, fmt::format("proto document is not JSON: {}", error.what()),
                  file);
    }
  }

  // Where the bundle keeps `file`: the root, or under /$defs/<file>.
  std::string prefixOf(const std::string& file) {
    if (file == rootFile_) return "";
    if (seen_.insert(file).second) pending_.push_back(file);
    return "/$defs/" + escapePointerToken(file);
  }

  std::string rewriteRef(const std::string& ref, const std::string& currentFile) {
    const std::size_t hash = ref.find('#');
    const std::string documentPart = ref.substr(0, hash);
    const std::string pointer = hash == std::string::npos ? "" : ref.substr(hash + 1);
    const std::string file = documentPart.empty() ? currentFile : fileNameOf(documentPart);
    if (!embedded::protoFiles().contains(file)) {
      throw Error(ErrorCode::Internal, fmt::format("$ref to an unknown document: {}", ref),
                  currentFile);
    }
    return "#" + prefixOf(file) + pointer;
  }

  // Schemas nest only as deep as the files are written, so recursion is bounded here.
  void rewriteRefs(json& node, const std::string& currentFile) {
    if (node.is_object()) {
      for (auto& [key, value] : node.items()) {
        if (key == "$ref" && value.is_string()) {
          value = rewriteRef(value.get<std::string>(), currentFile);
        } else if (key == "discriminator" && value.contains("mapping")) {
          // Mapping values are references too (OpenAPI): they must keep naming the oneOf's $refs.
          for (auto& [name, ref] : value["mapping"].items()) {
            if (ref.is_string()) ref = rewriteRef(ref.get<std::string>(), currentFile);
          }
        } else {
          rewriteRefs(value, currentFile);
        }
      }
    } else if (node.is_array()) {
      for (json& element : node) rewriteRefs(element, currentFile);
    }
  }

  // {"oneOf": [A, B], "discriminator": {"propertyName": "type", "mapping": {"a": A, "b": B}}}
  // becomes {"required": ["type"], "properties": {"type": {"enum": ["a", "b"]}},
  //          "allOf": [{"if": {type is "a"}, "then": A}, {"if": {type is "b"}, "then": B}]}
  // (members the node has already are kept). Runs after rewriteRefs: A and B are local pointers.
  static void lowerDiscriminator(json& node, const std::string& file) {
    const json& discriminator = node["discriminator"];
    const std::string property = discriminator.value("propertyName", "");
    const json mapping = discriminator.value("mapping", json::object());
    json branches = node["oneOf"];
    std::vector<std::string> mapped;
    json values = json::array();
    json conditions = node.value("allOf", json::array());
    for (const auto& [value, ref] : mapping.items()) {
      values.push_back(value);
      mapped.push_back(ref.get<std::string>());
      conditions.push_back(
          {{"if", {{"properties", {{property, {{"const", value}}}}}, {"required", {property}}}},
           {"then", {{"$ref", ref}}}});
    }
    std::vector<std::string> listed;
    for (const json& branch : branches) listed.push_back(branch.value("$ref", ""));
    std::sort(mapped.begin(), mapped.end());
    std::sort(listed.begin(), listed.end());
    if (property.empty() || mapped.empty() || mapped != listed) {
      throw Error(ErrorCode::Internal,
                  "a discriminator needs a propertyName and a mapping onto exactly the $refs of "
                  "its oneOf",
                  file);
    }
    json& required = node["required"];
    if (!required.is_array()) required = json::array();
    if (std::find(required.begin(), required.end(), property) == required.end()) {
      required.push_back(property);
    }
    json& propertySchema = node["properties"][property];
    if (!propertySchema.contains("enum")) propertySchema["enum"] = values;
    node["allOf"] = std::move(conditions);
    node.erase("oneOf");
    node.erase("discriminator");
  }

  // Bounded like rewriteRefs: as deep as the files are written.
  static void lowerDiscriminators(json& node, const std::string& file) {
    if (node.is_object()) {
      if (node.contains("discriminator") && node.contains("oneOf")) {
        lowerDiscriminator(node, file);
      }
      for (auto& [key, value] : node.items()) lowerDiscriminators(value, file);
    } else if (node.is_array()) {
      for (json& element : node) lowerDiscriminators(element, file);
    }
  }

  std::string rootFile_;
  std::set<std::string> seen_;
  std::vector<std::string> pending_;
};

}  // namespace

json bundleSchema(const std::string& rootFile) { return Bundler(rootFile).run(); }

}  // namespace lgh
