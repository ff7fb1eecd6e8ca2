#include "scene/asset_path.hpp"

#include <algorithm>
#include <system_error>

#include <fmt/format.h>

#include "lgh/error.hpp"

namespace lgh {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void reject(const std::string& relative, const std::string& why,
                         const std::string& field) {
  throw Error(ErrorCode::BadRequest, fmt::format("asset path '{}' {}", relative, why), field);
}

// True when every component of `root` is a leading component of `path` (both canonical).
bool isInside(const fs::path& path, const fs::path& root) {
  auto [rootEnd, pathIt] = std::mismatch(root.begin(), root.end(), path.begin(), path.end());
  return rootEnd == root.end() ||
         // A root spelled with a trailing separator ends in an empty component.
         (std::next(rootEnd) == root.end() && rootEnd->empty());
}

fs::path canonicalRoot(const fs::path& root, const std::string& field) {
  std::error_code error;
  fs::path canonical = fs::canonical(root, error);
  if (error || !fs::is_directory(canonical)) {
    // The root is the operator's configuration, not the request's: do not echo it.
    throw Error(ErrorCode::NotFound, "the asset root is not an existing directory", field);
  }
  return canonical;
}

}  // namespace

fs::path checkRelativeAssetPath(const std::string& relative, const std::string& field) {
  if (relative.empty()) {
    throw Error(ErrorCode::BadRequest, "asset path is empty", field);
  }
  if (relative.find('\0') != std::string::npos) {
    throw Error(ErrorCode::BadRequest, "asset path contains a NUL byte", field);
  }
  const fs::path path(relative);
  if (path.is_absolute() || path.has_root_path()) {
    reject(relative, "is absolute; paths are relative to the asset root", field);
  }
  for (const fs::path& component : path) {
    if (component == "..") reject(relative, "contains a '..' component", field);
  }
  fs::path normal = path.lexically_normal();
  if (normal.empty() || normal == ".") reject(relative, "names no file", field);
  return normal;
}

fs::path resolveAssetPath(const fs::path& root, const std::string& relative,
                          const std::string& field) {
  const fs::path normal = checkRelativeAssetPath(relative, field);
  const fs::path base = canonicalRoot(root, field);
  std::error_code error;
  // weakly_canonical resolves the symlinks of the existing prefix, so a link that points outside
  // the root is caught even when its target does not exist.
  fs::path resolved = fs::weakly_canonical(base / normal, error);
  if (error) reject(relative, fmt::format("cannot be resolved ({})", error.message()), field);
  if (!isInside(resolved, base)) reject(relative, "resolves outside the asset root", field);
  const fs::file_status status = fs::status(resolved, error);
  if (!fs::exists(status)) {
    throw Error(ErrorCode::NotFound, fmt::format("asset file '{}' not found", relative), field);
  }
  if (!fs::is_regular_file(status)) reject(relative, "is not a regular file", field);
  return resolved;
}

}  // namespace lgh
