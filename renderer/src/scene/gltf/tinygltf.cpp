// tinygltf is built here and only here, configured as tinygltf.hpp says.
// tinygltf's (unused) writer needs <fstream> but includes it only without TINYGLTF_NO_FS.
#include <fstream>

#define TINYGLTF_IMPLEMENTATION
#include "scene/gltf/tinygltf.hpp"

namespace lgh::gltf {

std::string percentDecodedUri(const std::string& uri) { return tinygltf::dlib::urldecode(uri); }

}  // namespace lgh::gltf
