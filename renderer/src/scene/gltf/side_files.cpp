#include "scene/gltf/side_files.hpp"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <vector>

#include <fmt/format.h>

#include "lgh/error.hpp"
#include "scene/asset_path.hpp"

namespace lgh::gltf {

std::string uriKey(const std::string& uri) {
  try {
    return checkRelativeAssetPath(uri, "").generic_string();
  } catch (const Error&) {
    return uri;
  }
}

namespace {

namespace fs = std::filesystem;

// "scheme:..." (http:, file:, ...): not a relative reference. data: URIs never get here.
bool hasUriScheme(const std::string& uri) {
  const auto colon = uri.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  return std::all_of(uri.begin(), uri.begin() + static_cast<std::ptrdiff_t>(colon), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
  });
}

struct SideFile {
  fs::path path;                                     // Directory
  const std::vector<std::uint8_t>* bytes = nullptr;  // Memory
};

// Resolves a (percent-decoded) URI of the model to a file: on disk inside the asset root, or in
// the uploaded files. Throws lgh::Error: Invalid for a sandbox violation, NotFound.
SideFile locateSideFile(const LoadContext& ctx, const std::string& uri) {
  if (ctx.sideFiles == SideFiles::None) {
    invalid(ctx, fmt::format("an inline .glb cannot reference the external file '{}'; embed it "
                             "(GLB buffer, bufferView image or data: URI)",
                             uri));
  }
  if (hasUriScheme(uri)) {
    invalid(ctx,
            fmt::format("URI '{}' is not supported: only relative file paths and data: URIs", uri));
  }
  fs::path relative;
  try {
    relative = checkRelativeAssetPath(uri, ctx.displayName);
  } catch (const Error& error) {
    invalid(ctx, fmt::format("URI rejected by the asset sandbox: {}", error.message()));
  }
  const std::string inModel = (ctx.baseDir / relative).lexically_normal().generic_string();
  if (ctx.sideFiles == SideFiles::Memory) {
    const auto it = ctx.memoryFiles.find(inModel);
    if (it == ctx.memoryFiles.end()) {
      throw Error(ErrorCode::NotFound,
                  fmt::format("file '{}' referenced by the asset was not uploaded", uri),
                  ctx.displayName);
    }
    return {{}, it->second};
  }
  try {
    return {resolveAssetPath(ctx.root, inModel, ctx.displayName)};
  } catch (const Error& error) {
    if (error.code() == ErrorCode::NotFound) {
      throw Error(ErrorCode::NotFound,
                  fmt::format("file '{}' referenced by the asset not found", uri), ctx.displayName);
    }
    invalid(ctx, fmt::format("URI rejected by the asset sandbox: {}", error.message()));
  }
}

// Missing and oversized files are per file (an unused image may be missing); anything else is a
// sandbox violation and fails the load however tinygltf goes on.
void recordFileError(LoadContext& ctx, const std::string& uri, const Error& error) {
  if (error.code() == ErrorCode::NotFound || error.code() == ErrorCode::TooLarge) {
    ctx.fileErrors.emplace(uriKey(uri), error);
  } else if (!ctx.fatal) {
    ctx.fatal = error;
  }
}

std::vector<std::uint8_t> readSideFile(const LoadContext& ctx, const std::string& uri,
                                       const SideFile& file) {
  const std::size_t size = file.bytes != nullptr
                               ? file.bytes->size()
                               : static_cast<std::size_t>(fs::file_size(file.path));
  if (size > ctx.limits.maxFileBytes) {
    tooLarge(ctx, fmt::format("file '{}' is {} bytes, over the limit of {}", uri, size,
                              ctx.limits.maxFileBytes));
  }
  if (file.bytes != nullptr) return *file.bytes;
  std::vector<std::uint8_t> bytes(size);
  std::ifstream stream(file.path, std::ios::binary);
  if (!stream.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) {
    throw Error(ErrorCode::NotFound, fmt::format("file '{}' could not be read", uri),
                ctx.displayName);
  }
  return bytes;
}

// tinygltf FsCallbacks. tinygltf hands over JoinPath(base_dir, uri) with the URI percent-decoded;
// we pass an empty base_dir, so the path is the decoded URI itself (its retry is "./" + URI).
bool fileExistsCallback(const std::string& path, void* user) {
  auto& ctx = *static_cast<LoadContext*>(user);
  try {
    locateSideFile(ctx, path);
    return true;
  } catch (const Error& error) {
    recordFileError(ctx, path, error);
    return false;
  }
}

std::string expandFilePathCallback(const std::string& path, void*) { return path; }

bool readWholeFileCallback(std::vector<unsigned char>* out, std::string* err,
                           const std::string& path, void* user) {
  auto& ctx = *static_cast<LoadContext*>(user);
  try {
    *out = readSideFile(ctx, path, locateSideFile(ctx, path));
    return true;
  } catch (const Error& error) {
    recordFileError(ctx, path, error);
    if (err != nullptr) *err += error.message();
    return false;
  } catch (const std::exception& error) {  // file_size races, bad_alloc
    recordFileError(ctx, path, Error(ErrorCode::NotFound, error.what(), ctx.displayName));
    if (err != nullptr) *err += error.what();
    return false;
  }
}

bool writeWholeFileCallback(std::string* err, const std::string&, const std::vector<unsigned char>&,
                            void*) {
  if (err != nullptr) *err += "the loader writes no files";
  return false;
}

}  // namespace

tinygltf::FsCallbacks sandboxedFileCallbacks(LoadContext& ctx) {
  return {&fileExistsCallback, &expandFilePathCallback, &readWholeFileCallback,
          &writeWholeFileCallback, &ctx};
}

}  // namespace lgh::gltf
