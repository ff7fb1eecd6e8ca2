// Side files: the buffers and images a model references by URI. tinygltf reads them only through
// the callbacks made here, which resolve every (percent-decoded) URI through the asset sandbox
// (resolveAssetPath: no "..", no absolute paths, no symlink leaving the root) or among the
// uploaded files, refuse any external file to an inline .glb, and record in the LoadContext why a
// file could not be had.
#pragma once

#include <string>

#include "scene/gltf/load_context.hpp"
#include "scene/gltf/tinygltf.hpp"

namespace lgh::gltf {

// A URI key independent of spelling ("./a.bin" and "a.bin" are one file): how
// LoadContext::fileErrors and LoadContext::memoryFiles are keyed.
std::string uriKey(const std::string& uri);

// tinygltf's file system callbacks, reading side files for `ctx`, which must outlive the parse.
// Missing and oversized files land in ctx.fileErrors (per file: an unused image may be missing);
// a sandbox violation lands in ctx.fatal and fails the load however tinygltf goes on.
tinygltf::FsCallbacks sandboxedFileCallbacks(LoadContext& ctx);

}  // namespace lgh::gltf
