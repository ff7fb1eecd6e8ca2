#include "uploads.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "api_error.hpp"

namespace lghd {
namespace {

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool hasExtension(const std::string& name, const std::string& extension) {
  const std::string lower = lowercase(name);
  return lower.size() > extension.size() && lower.ends_with(extension);
}

bool isModel(const std::string& name) {
  return hasExtension(name, ".glb") || hasExtension(name, ".gltf");
}

lgh::SceneSource glbScene(const UploadedFile& file) {
  lgh::SceneSource scene;
  scene.kind = lgh::SceneSource::Kind::InlineGlb;
  scene.glbBytes = file.bytes;
  scene.displayName = file.name;
  return scene;
}

lgh::SceneSource gltfScene(const UploadedFile& gltf, const std::vector<UploadedFile>& files) {
  lgh::SceneSource scene;
  scene.kind = lgh::SceneSource::Kind::UploadedGltf;
  scene.gltfFileName = gltf.name;
  scene.displayName = gltf.name;
  scene.uploadedFiles[gltf.name] = gltf.bytes;
  for (const UploadedFile& file : files) {
    if (!isModel(file.name)) scene.uploadedFiles[file.name] = file.bytes;
  }
  return scene;
}

}  // namespace

nlohmann::json requestPartJson(const httplib::Request& request) {
  if (!request.has_file("request")) return nlohmann::json::object();
  const std::string text = request.get_file_value("request").content;
  nlohmann::json json;
  try {
    json = lgh::parseRequestJson(text);
  } catch (const lgh::Error& error) {
    const ApiError answer = fromLghError(error);
    throw ApiError(answer.status(), answer.code(), answer.message(), "request");
  }
  if (!json.is_object()) throw badRequest("the request part must be a JSON object", "request");
  return json;
}

std::vector<UploadedFile> uploadedFiles(const httplib::Request& request) {
  std::vector<UploadedFile> files;
  std::set<std::string> names;
  const auto [begin, end] = request.files.equal_range("file");
  for (auto it = begin; it != end; ++it) {
    const httplib::MultipartFormData& part = it->second;
    if (part.filename.empty()) throw badRequest("every file part needs a filename", "file");
    if (!names.insert(part.filename).second) {
      throw badRequest(fmt::format("the file '{}' was uploaded twice", part.filename), "file");
    }
    files.push_back({part.filename, {part.content.begin(), part.content.end()}});
  }
  return files;
}

std::vector<lgh::SceneSource> uploadedScenes(const std::vector<UploadedFile>& files) {
  std::vector<lgh::SceneSource> scenes;
  for (const UploadedFile& file : files) {
    if (hasExtension(file.name, ".glb")) scenes.push_back(glbScene(file));
    if (hasExtension(file.name, ".gltf")) scenes.push_back(gltfScene(file, files));
  }
  return scenes;
}

lgh::SceneSource uploadedScene(const std::vector<UploadedFile>& files) {
  std::vector<lgh::SceneSource> scenes = uploadedScenes(files);
  if (scenes.size() != 1) {
    throw badRequest(fmt::format("upload exactly one .glb or .gltf file (with the .gltf's "
                                 "buffers and images as further file parts), got {}",
                                 scenes.size()),
                     "file");
  }
  return std::move(scenes.front());
}

}  // namespace lghd
