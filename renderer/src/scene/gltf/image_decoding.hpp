// Texture images. tinygltf decodes none itself: it hands each image's bytes to the callback
// here, which refuses an oversized texture from its PNG or JPEG header before the decoder
// allocates for it, then decodes through our image I/O to RGBA8.
#pragma once

#include <string>

#include "scene/gltf/tinygltf.hpp"

namespace lgh::gltf {

// "image 2 ('wood') 'textures/wood.png'": how messages name a glTF image.
std::string imageLabel(const tinygltf::Image& image, int index);

// tinygltf LoadImageDataFunction; `user` is the LoadContext, whose images (decoded, by glTF image
// index) or imageErrors receive the result. Never fails the parse: an image that cannot be
// decoded only matters if a material uses it (checked when textures are resolved).
bool loadImageCallback(tinygltf::Image* image, int index, std::string* err, std::string* warn,
                       int requestedWidth, int requestedHeight, const unsigned char* bytes,
                       int size, void* user);

}  // namespace lgh::gltf
