// glTF 2.0 (.gltf + side files, or .glb) -> Scene, through tinygltf, hardened for untrusted input:
//
//  - The JSON is checked against the parts of the glTF schema we consume before tinygltf sees it
//    (tinygltf silently ignores wrongly typed members); a type error is lgh::Error(Invalid) naming
//    the JSON pointer, e.g. "/meshes/0/primitives must be an array".
//  - Every external URI (percent-decoded by tinygltf) is resolved through the asset sandbox
//    (resolveAssetPath: no "..", no absolute paths, no symlink leaving the root). data: URIs are
//    fine; an inline .glb may reference no external file at all.
//  - Every accessor is bounds-checked by hand before it is read; indices are checked against the
//    vertex count; positions must be finite.
//
// What becomes an error and what is repaired (with a line in Scene::warnings):
//  - errors (lgh::Error): malformed JSON/GLB or schema type errors (Invalid, tinygltf's text),
//    missing buffer or used image file (NotFound), sandbox violations (Invalid for a URI inside
//    the asset, BadRequest for the asset path itself, as resolveAssetPath throws), unsupported
//    REQUIRED extensions (Invalid, naming them, unless options.ignoreUnsupportedExtensions), wrong
//    accessor type/componentType for an attribute, accessor or bufferView out of bounds, index >=
//    vertex count, non-finite POSITION, node cycles or hierarchies deeper than 64, limits exceeded
//    after decompression too (TooLarge: SceneLoadLimits, JSON nesting deeper than 64 levels or more
//    than 4 million values), an invalid GLB container (version, lengths, chunk types and
//    alignment), what document_check.hpp lists (Invalid, naming the JSON pointer), an image used by
//    a material that cannot be decoded (Invalid, naming it), a Draco or meshopt stream that does
//    not decode (Invalid), an animation index or material variant the asset lacks (Invalid, naming
//    the request field).
//  - an asset whose scene draws nothing loads as an empty scene, with a warning.
//  - repairs: a trailing partial triangle or line dropped; missing normals -> flat normals for
//    triangles (glTF's rule), unlit lines and points; zero/NaN normals -> area-weighted smooth
//    normals; missing or broken tangents -> generated (see tangents.hpp); unsupported optional
//    extensions ignored with a warning; an image no material uses that fails to load is dropped.
//  - poses: skins and morph targets are applied at load time, at the bind pose (node transforms
//    and weights as stored) or at options.animation; a skinned mesh comes out in world space.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace lgh {

// What the request chooses about a load: the pose, the material variant, whether unsupported
// required extensions are tolerated, and how textures are uploaded. Part of the scene cache's key.
struct SceneLoadOptions {
  std::optional<SceneAnimation> animation;   // none: the bind pose (node transforms as stored)
  std::string materialVariant;               // KHR_materials_variants name; "": the default
  bool ignoreUnsupportedExtensions = false;  // render anyway, with a warning
  TextureCompression textureCompression = TextureCompression::None;  // at upload
};

struct SceneLoadLimits {
  std::size_t maxTriangles = 20'000'000;  // drawn triangles (instances count)
  int maxTextureSize = 16384;             // largest width or height of a texture image
  // All texture images of the asset together, decoded to RGBA8 (every image is decoded, used or
  // not): a few KB of PNG or JPEG can claim a large image, and an asset can name the same data
  // in any number of images.
  std::size_t maxTextureBytes = 4ULL << 30;
  std::size_t maxFileBytes = 1ULL << 30;  // per file: the asset and each side file
};

// Loads a .gltf (with its external files) or .glb. Paths inside the asset (buffer and image URIs)
// must resolve inside assetRoot. The format is told by the content (GLB magic), not the name.
Scene loadGltfFile(const std::filesystem::path& assetRoot, const std::string& relativePath,
                   const SceneLoadLimits& limits = {}, const SceneLoadOptions& options = {});

// A .glb held in memory (a request's inline asset). It may use embedded buffers and data: URIs
// only.
Scene loadGlbBytes(const std::vector<std::uint8_t>& bytes, const std::string& displayName,
                   const SceneLoadLimits& limits = {}, const SceneLoadOptions& options = {});

// Uploaded .gltf (or .glb) with its side files held in memory (name -> bytes, names relative to
// the upload, "/"-separated), for the daemon's multipart uploads. URIs are resolved relative to
// gltfName's folder, with the same rules as on disk.
Scene loadGltfFromMemory(const std::string& gltfName,
                         const std::map<std::string, std::vector<std::uint8_t>>& files,
                         const SceneLoadLimits& limits = {}, const SceneLoadOptions& options = {});

// The scene of a request's SceneSource: a file under assetRoot, an inline or uploaded .glb, or an
// uploaded .gltf with its side files. Not for the demo scene (lgh::Error(Internal)).
Scene loadSceneSource(const SceneSource& source, const std::filesystem::path& assetRoot,
                      const SceneLoadLimits& limits, const SceneLoadOptions& options = {});

}  // namespace lgh
