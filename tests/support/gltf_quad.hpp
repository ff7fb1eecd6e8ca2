// A test asset: one textured unit quad as a .gltf and its .bin, whose material carries `extras`
// and whose texture 0 is the DDS file `imageUri` (through MSFT_texture_dds, so no PNG decoder is
// involved). Used by the unit tests of extras.lgh and by the scene parser worker's HTTP tests.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace lgh::test {

struct GltfQuad {
  std::string gltf;               // the document, named quad.gltf; its buffer is quad.bin
  std::vector<std::uint8_t> bin;  // positions, normals, UVs and indices
};

GltfQuad ddsTexturedQuad(const std::string& materialName, const std::string& imageUri,
                         const nlohmann::json& extras);

}  // namespace lgh::test
