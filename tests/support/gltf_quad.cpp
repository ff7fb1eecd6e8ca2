#include "gltf_quad.hpp"

namespace lgh::test {

GltfQuad ddsTexturedQuad(const std::string& materialName, const std::string& imageUri,
                         const nlohmann::json& extras) {
  using json = nlohmann::json;
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const std::vector<float> uvs = {0, 1, 1, 1, 1, 0, 0, 0};
  const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3};
  GltfQuad quad;
  auto append = [&quad](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    quad.bin.insert(quad.bin.end(), bytes, bytes + size);
  };
  append(positions.data(), 48);
  append(normals.data(), 48);
  append(uvs.data(), 32);
  append(indices.data(), 12);
  const json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"MSFT_texture_dds"}},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
            {"indices", 3},
            {"material", 0}}}}}}},
      {"materials",
       {{{"name", materialName},
         {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
         {"extras", extras}}}},
      {"textures", {{{"extensions", {{"MSFT_texture_dds", {{"source", 0}}}}}}}},
      {"images", {{{"uri", imageUri}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", 4},
         {"type", "VEC3"},
         {"min", {0, 0, 0}},
         {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 32}},
        {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 12}}}},
      {"buffers", {{{"uri", "quad.bin"}, {"byteLength", quad.bin.size()}}}}};
  quad.gltf = gltf.dump();
  return quad;
}

}  // namespace lgh::test
