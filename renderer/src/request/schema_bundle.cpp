#include "request/schema_bundle.hpp"

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
    // Referenced files are appended to pending_ while earlier ones are rewritten.
    for (std::size_t i = 0; i < pending_.size(); ++i) {
      const std::string file = pending_[i];
      json document = load(file);
      document.erase("$schema");
      document.erase("$id");
      rewriteRefs(document, file);
      root["definitions"][file] = std::move(document);
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

  // Where the bundle keeps `file`: the root, or under /definitions/<file>.
  std::string prefixOf(const std::string& file) {
    if (file == rootFile_) return "";
    if (seen_.insert(file).second) pending_.push_back(file);
    return "/definitions/" + escapePointerToken(file);
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
        } else {
          rewriteRefs(value, currentFile);
        }
      }
    } else if (node.is_array()) {
      for (json& element : node) rewriteRefs(element, currentFile);
    }
  }

  std::string rootFile_;
  std::set<std::string> seen_;
  std::vector<std::string> pending_;
};

}  // namespace

json bundleSchema(const std::string& rootFile) { return Bundler(rootFile).run(); }

}  // namespace lgh
