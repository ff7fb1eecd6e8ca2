// multipart/form-data uploads: the request JSON in a part named "request", files in parts named
// "file" (each with a filename). A .glb becomes an inline GLB scene; a .gltf becomes an uploaded
// glTF whose URIs resolve only among the other uploaded files (its buffers and images).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "lgh/request.hpp"

namespace lghd {

struct UploadedFile {
  std::string name;
  std::vector<std::uint8_t> bytes;
};

// The JSON object of the "request" part ({} when there is none). Throws ApiError 400.
nlohmann::json requestPartJson(const httplib::Request& request);

// The "file" parts in order. Throws ApiError 400 for a part without a filename or a name given
// twice.
std::vector<UploadedFile> uploadedFiles(const httplib::Request& request);

// One scene per model file (.glb or .gltf, by extension), in upload order; every other file is a
// side file available to each .gltf.
std::vector<lgh::SceneSource> uploadedScenes(const std::vector<UploadedFile>& files);

// The one scene of a render upload. Throws ApiError 400 unless exactly one model was uploaded.
lgh::SceneSource uploadedScene(const std::vector<UploadedFile>& files);

}  // namespace lghd
