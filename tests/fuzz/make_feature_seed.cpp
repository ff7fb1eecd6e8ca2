// Writes tests/fuzz/seeds/gltf/compressed_features.glb: one small GLB with the glTF features of
// issue 20 that Debian's assimp-testmodels lack, so that the glTF fuzz target reaches their
// decoders and the scene parser worker's messages carry them (test_http_scene_worker):
//   - EXT_meshopt_compression: a tetrahedron's vertices (POSITION + TEXCOORD_0, interleaved) and
//     indices, decoded into views of a fallback buffer without data;
//   - EXT_texture_webp: a lossless 4x4 WebP base colour texture, with KHR_texture_transform;
//   - KHR_materials_clearcoat, _sheen, _specular, _ior, _transmission, _volume, _unlit, _variants;
//   - a morph target with a mesh weight, a LINES and a POINTS primitive beside the triangles;
//   - an animation of the node's translation (scene.animation).
// The seed is checked in; make it again after changing this file:
//   g++ -std=c++20 -O1 tests/fuzz/make_feature_seed.cpp -o /tmp/make_feature_seed \
//     -lmeshoptimizer -lwebp && /tmp/make_feature_seed
//     tests/fuzz/seeds/gltf/compressed_features.glb
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <meshoptimizer.h>
#include <webp/encode.h>
#include <nlohmann/json.hpp>

namespace {

using json = nlohmann::json;

class Bin {
 public:
  // A bufferView of buffer 0 holding `bytes` (4-byte aligned).
  int add(json& doc, const void* data, std::size_t size) {
    while (bytes_.size() % 4 != 0) bytes_.push_back(0);
    doc["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", bytes_.size()}, {"byteLength", size}});
    const auto* first = static_cast<const std::uint8_t*>(data);
    bytes_.insert(bytes_.end(), first, first + size);
    return static_cast<int>(doc["bufferViews"].size()) - 1;
  }
  template <typename T>
  int add(json& doc, const std::vector<T>& values) {
    return add(doc, values.data(), values.size() * sizeof(T));
  }
  std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

int accessor(json& doc, json value) {
  doc["accessors"].push_back(std::move(value));
  return static_cast<int>(doc["accessors"].size()) - 1;
}

std::vector<std::uint8_t> glb(const json& doc, std::vector<std::uint8_t> bin) {
  std::string text = doc.dump();
  while (text.size() % 4 != 0) text.push_back(' ');
  while (bin.size() % 4 != 0) bin.push_back(0);
  std::vector<std::uint8_t> out;
  auto put32 = [&out](std::size_t value) {
    for (unsigned i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(value >> (8U * i)));
  };
  put32(0x46546C67);
  put32(2);
  put32(12 + 8 + text.size() + 8 + bin.size());
  put32(text.size());
  put32(0x4E4F534A);
  out.insert(out.end(), text.begin(), text.end());
  put32(bin.size());
  put32(0x004E4942);
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_feature_seed OUT.glb\n");
    return 2;
  }
  json doc = {{"asset", {{"version", "2.0"}, {"generator", "lghd tests/fuzz/make_feature_seed"}}},
              {"scene", 0},
              {"scenes", {{{"nodes", {0}}}}}};
  Bin bin;

  // The tetrahedron, meshopt-encoded into views 0 and 1.
  struct Vertex {
    float position[3];
    float uv[2];
  };
  const std::vector<Vertex> vertices = {{{0, 1, 0}, {0.5F, 0}},
                                        {{-1, -0.6F, 0.6F}, {0, 1}},
                                        {{1, -0.6F, 0.6F}, {1, 1}},
                                        {{0, -0.6F, -1}, {0.5F, 0.5F}}};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};
  std::vector<unsigned char> vertexStream(
      meshopt_encodeVertexBufferBound(vertices.size(), sizeof(Vertex)));
  vertexStream.resize(meshopt_encodeVertexBuffer(vertexStream.data(), vertexStream.size(),
                                                 vertices.data(), vertices.size(), sizeof(Vertex)));
  std::vector<unsigned char> indexStream(
      meshopt_encodeIndexBufferBound(indices.size(), vertices.size()));
  indexStream.resize(meshopt_encodeIndexBuffer(indexStream.data(), indexStream.size(),
                                               indices.data(), indices.size()));
  const int vertexSource = bin.add(doc, vertexStream);
  const int indexSource = bin.add(doc, indexStream);
  // Buffer 1: the fallback the decoded views lie in; it has no data of its own.
  const std::size_t vertexBytes = vertices.size() * sizeof(Vertex);
  const std::size_t indexBytes = indices.size() * 4;
  auto meshoptView = [&](int source, std::size_t offset, std::size_t length, std::size_t stride,
                         std::size_t count, const char* mode) {
    const json& from = doc["bufferViews"][source];
    json view = {{"buffer", 1},
                 {"byteOffset", offset},
                 {"byteLength", length},
                 {"extensions",
                  {{"EXT_meshopt_compression",
                    {{"buffer", 0},
                     {"byteOffset", from["byteOffset"]},
                     {"byteLength", from["byteLength"]},
                     {"byteStride", stride},
                     {"count", count},
                     {"mode", mode}}}}}};
    if (std::string(mode) == "ATTRIBUTES") view["byteStride"] = stride;
    doc["bufferViews"].push_back(view);
    return static_cast<int>(doc["bufferViews"].size()) - 1;
  };
  const int vertexView =
      meshoptView(vertexSource, 0, vertexBytes, sizeof(Vertex), vertices.size(), "ATTRIBUTES");
  const int indexView =
      meshoptView(indexSource, vertexBytes, indexBytes, 4, indices.size(), "TRIANGLES");
  const int position = accessor(doc, {{"bufferView", vertexView},
                                      {"componentType", 5126},
                                      {"count", vertices.size()},
                                      {"type", "VEC3"},
                                      {"min", {-1, -0.6, -1}},
                                      {"max", {1, 1, 0.6}}});
  const int uv = accessor(doc, {{"bufferView", vertexView},
                                {"byteOffset", 12},
                                {"componentType", 5126},
                                {"count", vertices.size()},
                                {"type", "VEC2"}});
  const int index = accessor(doc, {{"bufferView", indexView},
                                   {"componentType", 5125},
                                   {"count", indices.size()},
                                   {"type", "SCALAR"}});
  // A morph target lifting the apex, plain.
  const std::vector<float> lift = {0, 0.5F, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const int target = accessor(doc, {{"bufferView", bin.add(doc, lift)},
                                    {"componentType", 5126},
                                    {"count", 4},
                                    {"type", "VEC3"},
                                    {"min", {0, 0, 0}},
                                    {"max", {0, 0.5, 0}}});

  // Lines (a square around the tetrahedron) and points (three), plain.
  const std::vector<float> square = {-1.5F, -0.8F, 0, 1.5F, -0.8F, 0, 1.5F,  -0.8F, 0,
                                     1.5F,  1.2F,  0, 1.5F, 1.2F,  0, -1.5F, 1.2F,  0};
  const int lines = accessor(doc, {{"bufferView", bin.add(doc, square)},
                                   {"componentType", 5126},
                                   {"count", 6},
                                   {"type", "VEC3"},
                                   {"min", {-1.5, -0.8, 0}},
                                   {"max", {1.5, 1.2, 0}}});
  const std::vector<float> dots = {-1.2F, 1.0F, 0.5F, 1.2F, 1.0F, 0.5F, 0, -0.8F, 1.0F};
  const int points = accessor(doc, {{"bufferView", bin.add(doc, dots)},
                                    {"componentType", 5126},
                                    {"count", 3},
                                    {"type", "VEC3"},
                                    {"min", {-1.2, -0.8, 0.5}},
                                    {"max", {1.2, 1.0, 1.0}}});

  // Every primitive of a mesh has as many morph targets as the others: these two move nothing.
  auto still = [&](std::size_t count) {
    const std::vector<float> zeros(count * 3, 0.0F);
    return accessor(doc, {{"bufferView", bin.add(doc, zeros)},
                          {"componentType", 5126},
                          {"count", count},
                          {"type", "VEC3"},
                          {"min", {0, 0, 0}},
                          {"max", {0, 0, 0}}});
  };
  const int linesTarget = still(6);
  const int pointsTarget = still(3);

  // A lossless 4x4 WebP: a colour checker.
  std::vector<std::uint8_t> rgba;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      const bool odd = ((x + y) % 2) != 0;
      rgba.insert(rgba.end(),
                  {static_cast<std::uint8_t>(odd ? 230 : 40), static_cast<std::uint8_t>(x * 60),
                   static_cast<std::uint8_t>(y * 60), 255});
    }
  }
  std::uint8_t* webp = nullptr;
  const std::size_t webpSize = WebPEncodeLosslessRGBA(rgba.data(), 4, 4, 16, &webp);
  if (webpSize == 0) return 1;
  const int imageView = bin.add(doc, webp, webpSize);
  WebPFree(webp);
  doc["images"] = {{{"bufferView", imageView}, {"mimeType", "image/webp"}}};
  doc["samplers"] = {{{"magFilter", 9728}, {"minFilter", 9728}}};
  doc["textures"] = {{{"sampler", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}};

  doc["materials"] = {
      {{"name", "layered"},
       {"pbrMetallicRoughness",
        {{"baseColorTexture",
          {{"index", 0},
           {"extensions",
            {{"KHR_texture_transform",
              {{"offset", {0.25, 0}}, {"rotation", 0.5}, {"scale", {2, 2}}}}}}}},
         {"metallicFactor", 0.1},
         {"roughnessFactor", 0.6}}},
       {"extensions",
        {{"KHR_materials_clearcoat", {{"clearcoatFactor", 0.7}, {"clearcoatRoughnessFactor", 0.2}}},
         {"KHR_materials_sheen",
          {{"sheenColorFactor", {0.3, 0.2, 0.9}}, {"sheenRoughnessFactor", 0.4}}},
         {"KHR_materials_specular",
          {{"specularFactor", 0.8}, {"specularColorFactor", {1, 0.9, 0.8}}}},
         {"KHR_materials_ior", {{"ior", 1.4}}},
         {"KHR_materials_transmission", {{"transmissionFactor", 0.3}}},
         {"KHR_materials_volume",
          {{"thicknessFactor", 0.5},
           {"attenuationDistance", 2},
           {"attenuationColor", {0.9, 0.6, 0.5}}}}}}},
      {{"name", "red unlit"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.1, 0.1, 1}}}},
       {"extensions", {{"KHR_materials_unlit", json::object()}}}}};

  doc["meshes"] = {
      {{"primitives",
        {{{"attributes", {{"POSITION", position}, {"TEXCOORD_0", uv}}},
          {"indices", index},
          {"material", 0},
          {"targets", {{{"POSITION", target}}}},
          {"extensions",
           {{"KHR_materials_variants", {{"mappings", {{{"material", 1}, {"variants", {0}}}}}}}}}},
         {{"attributes", {{"POSITION", lines}}},
          {"mode", 1},
          {"material", 1},
          {"targets", {{{"POSITION", linesTarget}}}}},
         {{"attributes", {{"POSITION", points}}},
          {"mode", 0},
          {"targets", {{{"POSITION", pointsTarget}}}}}}},
       {"weights", {0.5}}}};
  doc["nodes"] = {{{"mesh", 0}, {"rotation", {0, 0.3826834, 0, 0.9238795}}}};

  // The node's translation from (0, 0, 0) at 0 s to (0, 0.5, 0) at 1 s.
  const std::vector<float> times = {0, 1};
  const std::vector<float> moves = {0, 0, 0, 0, 0.5F, 0};
  const int input = accessor(doc, {{"bufferView", bin.add(doc, times)},
                                   {"componentType", 5126},
                                   {"count", 2},
                                   {"type", "SCALAR"},
                                   {"min", {0}},
                                   {"max", {1}}});
  const int output = accessor(doc, {{"bufferView", bin.add(doc, moves)},
                                    {"componentType", 5126},
                                    {"count", 2},
                                    {"type", "VEC3"}});
  doc["animations"] = {
      {{"samplers", {{{"input", input}, {"output", output}}}},
       {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}};

  doc["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "red"}}};
  doc["extensionsUsed"] = {
      "EXT_meshopt_compression", "EXT_texture_webp",           "KHR_texture_transform",
      "KHR_materials_clearcoat", "KHR_materials_sheen",        "KHR_materials_specular",
      "KHR_materials_ior",       "KHR_materials_transmission", "KHR_materials_volume",
      "KHR_materials_unlit",     "KHR_materials_variants"};
  doc["extensionsRequired"] = {"EXT_meshopt_compression", "EXT_texture_webp"};
  while (bin.bytes().size() % 4 != 0) bin.bytes().push_back(0);
  doc["buffers"] = {{{"byteLength", bin.bytes().size()}},
                    {{"byteLength", vertexBytes + indexBytes},
                     {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};

  const std::vector<std::uint8_t> bytes = glb(doc, bin.bytes());
  std::ofstream(argv[1], std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  return 0;
}
