// Compressed geometry decoded into plain glTF buffers before the scene is built, so that every
// later stage reads it through the same bounds-checked accessors and limits as uncompressed data:
//  - KHR_draco_mesh_compression (libdraco): each compressed primitive's stream is decoded, and the
//    accessors its attributes and indices name are pointed at new buffers holding the result
//    (floats; joints as unsigned shorts; indices as unsigned ints).
//  - EXT_meshopt_compression (libmeshoptimizer): each compressed bufferView is decoded (with its
//    filter) into a new buffer, and the bufferView is pointed there.
// Decoded sizes are checked against the triangle limit before anything is allocated for them, and
// a stream that does not decode is lgh::Error(Invalid) naming the primitive or bufferView.
#pragma once

#include "scene/gltf/load_context.hpp"
#include "scene/gltf/tinygltf.hpp"

namespace lgh::gltf {

void decompressGeometry(tinygltf::Model& model, LoadContext& ctx);

}  // namespace lgh::gltf
