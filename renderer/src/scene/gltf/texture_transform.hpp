// KHR_texture_transform on a textureInfo: offset, rotation, scale and the texCoord override.
#pragma once

#include <string>

#include "scene/gltf/load_context.hpp"
#include "scene/gltf/tinygltf.hpp"
#include "scene/scene.hpp"

namespace lgh::gltf {

// The transform of a textureInfo's extensions (identity without KHR_texture_transform). A
// texCoord given there replaces `texCoord`, as the extension says. Non-finite values are replaced
// by the defaults, with a warning naming `owner`.
UvTransform readTextureTransform(const tinygltf::ExtensionMap& extensions, const std::string& owner,
                                 LoadContext& ctx, int& texCoord);

}  // namespace lgh::gltf
