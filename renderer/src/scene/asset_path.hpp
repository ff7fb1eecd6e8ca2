// The asset sandbox: every file the renderer reads on behalf of a request (the asset itself and
// each buffer or image its glTF references) goes through resolveAssetPath, so that no request can
// read outside the configured asset root.
#pragma once

#include <filesystem>
#include <string>

namespace lgh {

// Checks `relative` without touching the file system: not empty, no NUL byte, not absolute, no
// `..` component. Throws lgh::Error(BadRequest, ..., field) otherwise. Returns the lexically
// normalised path ("./a//b" -> "a/b").
std::filesystem::path checkRelativeAssetPath(const std::string& relative, const std::string& field);

// `root / relative`, canonical (symlinks resolved), after checkRelativeAssetPath. Throws
// lgh::Error:
//  - BadRequest when the resolved path leaves canonical(root) (a symlink pointing outside counts)
//    or is not a regular file;
//  - NotFound (naming `relative`, never the server's absolute path) when it does not exist.
// The check is made at call time; a symlink swapped afterwards is not caught (the asset root is
// the operator's, not the requester's, so that race is out of scope).
std::filesystem::path resolveAssetPath(const std::filesystem::path& root,
                                       const std::string& relative, const std::string& field);

}  // namespace lgh
