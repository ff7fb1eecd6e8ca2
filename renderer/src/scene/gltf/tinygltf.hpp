// tinygltf as the glTF loader configures it. Every file that uses tinygltf includes it through
// this header, because the configuration macros change the TinyGLTF class itself and must agree
// everywhere. tinygltf decodes no images itself (our image I/O does, through SetImageLoader; see
// image_decoding.hpp) and has no file system access of its own (TINYGLTF_NO_FS): every side file
// is read through the sandboxed callbacks of side_files.hpp. Its implementation is built in
// tinygltf.cpp, and only there.
#pragma once

#include <string>

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_FS
#include <tiny_gltf.h>

namespace lgh::gltf {

// tinygltf's own percent-decoding of a URI (dlib::urldecode, which only its implementation
// sees): the path its file system callbacks are handed for that URI.
std::string percentDecodedUri(const std::string& uri);

}  // namespace lgh::gltf
