// What one load of a glTF asset carries from stage to stage: the caller's limits, where side
// files come from, what the tinygltf callbacks found (decoded images, per-file errors) and the
// warnings that end up in Scene::warnings. Also the two ways a stage fails the load, and how
// messages name glTF objects.
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lgh/error.hpp"
#include "lgh/image.hpp"
#include "scene/block_compression.hpp"
#include "scene/gltf/gltf_loader.hpp"

namespace lgh::gltf {

// Where a model's side files (buffers and images referenced by URI) come from.
enum class SideFiles { Directory, Memory, None };

// What the tinygltf callbacks need, and what they found.
struct LoadContext {
  std::string displayName;
  SceneLoadLimits limits;
  SceneLoadOptions options;
  SideFiles sideFiles = SideFiles::None;
  std::filesystem::path root;  // Directory: the asset root
  // Directory, Memory: the model's folder, relative (to root / to the upload)
  std::filesystem::path baseDir;
  std::map<std::string, const std::vector<std::uint8_t>*> memoryFiles;  // normalised name
  std::optional<Error> fatal;                       // a sandbox violation: always fails the load
  std::map<std::string, Error> fileErrors;          // missing / too large side files, by URI
  std::map<int, Image8> images;                     // decoded, by glTF image index
  std::map<int, BlockCompressedImage> blockImages;  // DDS blocks as loaded, by glTF image index
  std::map<int, Error> imageErrors;                 // decode failures, by glTF image index
  std::size_t decodedTextureBytes = 0;              // of all images decoded so far
  std::vector<std::string> warnings;

  void warnOnce(const std::string& warning) {
    if (std::find(warnings.begin(), warnings.end(), warning) == warnings.end()) {
      warnings.push_back(warning);
    }
  }
};

// Throws lgh::Error(Invalid, message), naming the asset.
[[noreturn]] void invalid(const LoadContext& ctx, const std::string& message);

// Throws lgh::Error(TooLarge, message), naming the asset.
[[noreturn]] void tooLarge(const LoadContext& ctx, const std::string& message);

// "/meshes/3 ('Teapot')", or "/meshes/3" when unnamed: how messages name glTF objects, by the
// JSON pointer of the object (`array` is the document's array: "meshes", "nodes", ...).
std::string label(const char* array, int index, const std::string& name);

}  // namespace lgh::gltf
