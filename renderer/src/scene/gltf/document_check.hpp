// What the glTF 2.0 specification requires of a document beyond its schema's types, checked on the
// JSON (after checkSchema) before tinygltf sees it, as the Khronos validator checks it
// (docs/TESTING.md lists where lghd and the validator still differ):
//   - every index names an object that exists (the validator's UNRESOLVED_REFERENCE), so that
//     neither tinygltf nor the loader ever follows a dangling index;
//   - extensions are declared in extensionsUsed, and required ones are used;
//   - the node hierarchy is a set of disjoint strict trees: no node twice in one children list,
//     no node with two parents, no loops, scenes list roots only;
//   - a node has either matrix or translation/rotation/scale, and its matrix is affine;
//   - every bufferView lies inside its buffer and every accessor (sparse parts included) inside
//     its bufferView, at offsets aligned to its component size, with a byteStride at least its
//     element size; bufferViews shared by vertex attributes declare byteStride;
//   - data: URIs of buffers are valid base64 that decodes to the declared byteLength, and a GLB
//     buffer without URI has a BIN chunk to take its bytes from;
//   - primitives: TEXCOORD_n and COLOR_n sets without gaps, every attribute with the same count,
//     and the texture coordinate sets their material samples.
// Each failure is lgh::Error(Invalid) whose message starts with the JSON pointer at fault, e.g.
// "invalid glTF: /nodes/0/camera names camera 3, which does not exist (the asset has 1)".
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace lgh::gltf {

struct DocumentContext {
  std::string displayName;
  std::optional<std::size_t> glbBinBytes;  // a GLB: its BIN chunk's size (0 when it has none)
};

void checkDocument(const nlohmann::json& document, const DocumentContext& context);

}  // namespace lgh::gltf
