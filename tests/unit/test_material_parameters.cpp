// Material parameters without GL: the request's `materials` (parsed, checked, errors naming the
// field), their application per frame (MaterialTable: the cached scene untouched), glTF
// extras.lgh (the same parameters, errors naming the material), per-light colours, and
// block-compressed textures (BC1-BC5 decoding of hand-made blocks, DDS files read and written,
// MSFT_texture_dds in an asset).
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gltf_quad.hpp"
#include "lgh/base64.hpp"
#include "lgh/error.hpp"
#include "lgh/request.hpp"
#include "scene/block_compression.hpp"
#include "scene/dds_file.hpp"
#include "scene/demo_scene.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/material_table.hpp"

namespace {

using json = nlohmann::json;

// The error a callable throws: its code and field.
template <typename F>
lgh::Error errorOf(F&& f) {
  try {
    f();
  } catch (const lgh::Error& error) {
    return error;
  }
  ADD_FAILURE() << "no lgh::Error thrown";
  return lgh::Error(lgh::ErrorCode::Internal, "none", "");
}

lgh::RenderRequest requestWith(const json& materials) {
  return lgh::parseRenderRequest(json{{"materials", materials}});
}

// --- The request ------------------------------------------------------------------------------

TEST(MaterialRequest, ParsesEveryParameter) {
  const lgh::RenderRequest request = requestWith(json::array(
      {{{"match", {{"name", "red"}}},
        {"parameters",
         {{"model", "blinn-phong"},
          {"shading", "gouraud"},
          {"diffuse", {0.5, 0.4, 0.3}},
          {"ambient", {0.1, 0.1, 0.1}},
          {"specular", {0.9, 0.9, 0.9}},
          {"shininess", 64},
          {"specular_texture", {{"texture", 1}}},
          {"light_map", {{"texture", 3}}},
          {"height_texture", {{"texture", 1}, {"tex_coord", 1}}},
          {"surface", "relief"},
          {"height_scale", 0.1},
          {"relief_silhouettes", true},
          {"alpha_mode", "blend"},
          {"sampling",
           {{"wrap_s", "clamp-to-border"},
            {"border_color", {1, 0, 0, 1}},
            {"filter", "bicubic"},
            {"mipmaps", "nearest"},
            {"anisotropy", 8}}}}}},
       {{"match", {{"index", 2}}}, {"parameters", {{"model", "oren-nayar"}, {"sigma", 0.4}}}},
       {{"match", {{"all", true}}}, {"parameters", {{"model", "cook-torrance"}, {"m", 0.2}}}}}));
  ASSERT_EQ(request.materials.size(), 3U);
  const lgh::MaterialOverride& first = request.materials[0];
  EXPECT_EQ(first.match.kind, lgh::MaterialMatch::Kind::Name);
  EXPECT_EQ(first.match.name, "red");
  const lgh::MaterialParameters& p = first.parameters;
  EXPECT_EQ(p.model, lgh::MaterialModel::BlinnPhong);
  EXPECT_EQ(p.shading, lgh::ShadingMode::Gouraud);
  EXPECT_EQ(p.shininess, 64.0F);
  EXPECT_EQ(p.lightMap->texture, 3);
  EXPECT_EQ(p.lightMap->texCoord, 1);  // light maps default to the second UV set
  EXPECT_EQ(p.specularTexture->texCoord, 0);
  EXPECT_EQ(p.heightTexture->texCoord, 1);
  EXPECT_EQ(p.surface, lgh::SurfaceDetail::Relief);
  EXPECT_EQ(p.reliefSilhouettes, true);
  EXPECT_EQ(p.alphaMode, lgh::AlphaMode::Blend);
  EXPECT_EQ(p.sampling.wrapS, lgh::WrapMode::ClampToBorder);
  EXPECT_FALSE(p.sampling.wrapT.has_value());
  EXPECT_EQ(p.sampling.filter, lgh::TextureFilter::Bicubic);
  EXPECT_EQ(p.sampling.mipmaps, lgh::MipmapMode::Nearest);
  EXPECT_EQ(p.sampling.anisotropy, 8.0F);
  EXPECT_FALSE(p.sigma.has_value());
  EXPECT_EQ(request.materials[1].match.kind, lgh::MaterialMatch::Kind::Index);
  EXPECT_EQ(request.materials[1].match.index, 2);
  EXPECT_EQ(request.materials[2].match.kind, lgh::MaterialMatch::Kind::All);
}

TEST(MaterialRequest, BadParametersNameTheField) {
  struct Case {
    json materials;
    lgh::ErrorCode code;
    std::string field;
  };
  const std::vector<Case> cases = {
      {{{{"match", {{"name", "red"}}}, {"parameters", {{"shininess", 5000}}}}},
       lgh::ErrorCode::Invalid,
       "/materials/0/parameters/shininess"},
      {{{{"match", {{"name", "red"}}}, {"parameters", {{"sigma", -0.1}}}}},
       lgh::ErrorCode::Invalid,
       "/materials/0/parameters/sigma"},
      {{{{"match", {{"name", "red"}}}, {"parameters", {{"model", "ward"}}}}},
       lgh::ErrorCode::BadRequest,
       "/materials/0/parameters/model"},
      {{{{"match", {{"name", "red"}}}, {"parameters", {{"sampling", {{"anisotropy", 32}}}}}}},
       lgh::ErrorCode::Invalid,
       "/materials/0/parameters/sampling/anisotropy"},
      {{{{"match", {{"name", "red"}}}, {"parameters", {{"light_map", {{"tex_coord", 1}}}}}}},
       lgh::ErrorCode::BadRequest,
       "/materials/0/parameters/light_map"},
      {{{{"match", {{"name", "red"}, {"index", 1}}}, {"parameters", json::object()}}},
       lgh::ErrorCode::BadRequest,
       "/materials/0/match"},
      {{{{"match", {{"name", "red"}}}, {"parameters", {{"glossiness", 1}}}}},
       lgh::ErrorCode::BadRequest,
       "/materials/0/parameters"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.materials.dump());
    const lgh::Error error = errorOf([&] { requestWith(c.materials); });
    EXPECT_EQ(error.code(), c.code) << error.what();
    EXPECT_EQ(error.field().rfind(c.field, 0), 0U) << error.field() << ": " << error.what();
  }
}

TEST(MaterialRequest, PerLightColoursAndCompression) {
  const lgh::RenderRequest request = lgh::parseRenderRequest(
      json{{"lights",
            {{{"type", "point"}, {"ambient", {0.1, 0.2, 0.3}}, {"specular", {0, 0, 1}}},
             {{"type", "point"}}}},
           {"settings", {{"texture_compression", "bc"}}}});
  const lgh::LightDesc& lit = request.lights[0];
  EXPECT_EQ(lit.ambient, (std::array<float, 3>{0.1F, 0.2F, 0.3F}));
  EXPECT_FALSE(lit.diffuse.has_value());  // the light's colour
  EXPECT_EQ(*lit.specular, (std::array<float, 3>{0, 0, 1}));
  EXPECT_EQ(request.lights[1].ambient, (std::array<float, 3>{0, 0, 0}));
  EXPECT_EQ(request.settings.textureCompression, lgh::TextureCompression::Bc);
}

// --- Applied per frame ------------------------------------------------------------------------

lgh::MaterialOverride override(const json& match, const json& parameters) {
  return requestWith(json::array({{{"match", match}, {"parameters", parameters}}})).materials[0];
}

TEST(MaterialTable, AppliesOverridesWithoutTouchingTheScene) {
  const lgh::Scene scene = lgh::makeDemoScene();
  const lgh::MaterialTable table(
      scene, {override({{"name", "red"}}, {{"model", "phong"}, {"shininess", 12}}),
              override({{"index", 1}}, {{"model", "oren-nayar"}, {"sigma", 0.7}}),
              override({{"all", true}}, {{"sampling",
                                          {{"wrap_s", "clamp-to-border"},
                                           {"border_color", {1, 0, 0, 1}},
                                           {"filter", "nearest"}}}})});
  const auto index = [&](const std::string& name) {
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
      if (scene.materials[i].name == name) return static_cast<int>(i);
    }
    return -1;
  };
  EXPECT_EQ(table.at(index("red")).model, lgh::MaterialModel::Phong);
  EXPECT_EQ(table.at(index("red")).classic.shininess, 12.0F);
  EXPECT_EQ(table.at(1).model, lgh::MaterialModel::OrenNayar);
  EXPECT_EQ(table.at(1).classic.sigma, 0.7F);
  const lgh::Sampler& floor = table.at(index("floor_checker")).baseColorTexture.sampler;
  EXPECT_EQ(floor.wrapS, 0x812D);      // GL_CLAMP_TO_BORDER
  EXPECT_EQ(floor.wrapT, 0x2901);      // GL_REPEAT, as it was
  EXPECT_EQ(floor.magFilter, 0x2600);  // GL_NEAREST
  EXPECT_EQ(floor.minFilter, 0x2702);  // GL_NEAREST_MIPMAP_LINEAR: the mipmaps kept
  EXPECT_EQ(floor.borderColor, glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(table.at(-1).baseColorTexture.sampler.wrapS, 0x812D) << "the default material too";
  // The cached scene keeps its own materials.
  EXPECT_EQ(scene.materials[static_cast<std::size_t>(index("red"))].model,
            lgh::MaterialModel::MetallicRoughness);
  EXPECT_EQ(scene.materials[0].baseColorTexture.sampler.wrapS, 0x2901);
}

TEST(MaterialTable, ErrorsNameTheRequestField) {
  const lgh::Scene scene = lgh::makeDemoScene();
  struct Case {
    json match;
    json parameters;
    std::string field;
  };
  const std::vector<Case> cases = {
      {{{"name", "marble"}}, json::object(), "/materials/0/match/name"},
      {{{"index", 99}}, json::object(), "/materials/0/match/index"},
      {{{"name", "red"}}, {{"shading", "gouraud"}}, "/materials/0/parameters/shading"},
      {{{"name", "red"}},
       {{"model", "metallic-roughness"}, {"shading", "flat"}},
       "/materials/0/parameters/shading"},
      {{{"name", "red"}}, {{"surface", "relief"}}, "/materials/0/parameters/surface"},
      {{{"name", "red"}},
       {{"light_map", {{"texture", 99}}}},
       "/materials/0/parameters/light_map/texture"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.parameters.dump());
    const lgh::Error error =
        errorOf([&] { const lgh::MaterialTable table(scene, {override(c.match, c.parameters)}); });
    EXPECT_EQ(error.code(), lgh::ErrorCode::Invalid);
    EXPECT_EQ(error.field(), c.field) << error.what();
  }
  const lgh::Error named = errorOf([&] {
    const lgh::MaterialTable table(scene, {override({{"name", "marble"}}, json::object())});
  });
  EXPECT_NE(std::string(named.what()).find("'red'"), std::string::npos) << "lists the names";
}

// --- Block compression --------------------------------------------------------------------------

TEST(BlockCompression, DecodesHandMadeBlocks) {
  // BC1, four-colour mode (c0 > c1): red and blue, indices 0, 1, 2, 3 in the first row.
  const std::vector<std::uint8_t> bc1 = {0x00, 0xF8, 0x1F, 0x00, 0xE4, 0x00, 0x00, 0x00};
  const lgh::Image8 colors = lgh::decodeBlocks(lgh::BlockFormat::Bc1, 4, 4, bc1.data());
  auto texel = [](const lgh::Image8& image, int x, int y) {
    const std::uint8_t* p = &image.pixels[(static_cast<std::size_t>(y) * image.width + x) * 4];
    return std::array<int, 4>{p[0], p[1], p[2], p[3]};
  };
  EXPECT_EQ(texel(colors, 0, 0), (std::array<int, 4>{255, 0, 0, 255}));
  EXPECT_EQ(texel(colors, 1, 0), (std::array<int, 4>{0, 0, 255, 255}));
  EXPECT_EQ(texel(colors, 2, 0), (std::array<int, 4>{170, 0, 85, 255}));
  EXPECT_EQ(texel(colors, 3, 0), (std::array<int, 4>{85, 0, 170, 255}));
  EXPECT_EQ(texel(colors, 0, 1), (std::array<int, 4>{255, 0, 0, 255}));
  // BC1 three-colour mode (c0 <= c1): index 3 is transparent black.
  const std::vector<std::uint8_t> punch = {0x1F, 0x00, 0x00, 0xF8, 0xFF, 0xFF, 0xFF, 0xFF};
  EXPECT_EQ(texel(lgh::decodeBlocks(lgh::BlockFormat::Bc1, 4, 4, punch.data()), 2, 2),
            (std::array<int, 4>{0, 0, 0, 0}));
  // BC4: 200 and 100 with six steps between; indices 0, 1, 2 first.
  const std::vector<std::uint8_t> bc4 = {200, 100, 0x88, 0x00, 0x00, 0x00, 0x00, 0x00};
  const lgh::Image8 red = lgh::decodeBlocks(lgh::BlockFormat::Bc4, 4, 4, bc4.data());
  EXPECT_EQ(texel(red, 0, 0)[0], 200);
  EXPECT_EQ(texel(red, 1, 0)[0], 100);
  EXPECT_EQ(texel(red, 2, 0)[0], (6 * 200 + 100) / 7);
  // BC5: two BC4 blocks, red then green.
  std::vector<std::uint8_t> bc5 = bc4;
  bc5.insert(bc5.end(), {50, 60, 0, 0, 0, 0, 0, 0});
  const auto rg = texel(lgh::decodeBlocks(lgh::BlockFormat::Bc5, 4, 4, bc5.data()), 0, 0);
  EXPECT_EQ(rg, (std::array<int, 4>{200, 50, 0, 255}));
  // A 6 x 5 image takes 2 x 2 blocks.
  EXPECT_EQ(lgh::blockLevelBytes(lgh::BlockFormat::Bc3, 6, 5), 64U);
}

lgh::BlockCompressedImage twoLevelBc1() {
  lgh::BlockCompressedImage image;
  image.format = lgh::BlockFormat::Bc1;
  image.width = 8;
  image.height = 4;
  image.levels = {std::vector<std::uint8_t>(16, 0x11), std::vector<std::uint8_t>(8, 0x22),
                  std::vector<std::uint8_t>(8, 0x33), std::vector<std::uint8_t>(8, 0x44)};
  return image;
}

TEST(DdsFile, RoundTripAndBoundsChecks) {
  for (const bool srgb : {false, true}) {
    lgh::BlockCompressedImage image = twoLevelBc1();
    image.srgb = srgb;
    const std::vector<std::uint8_t> file = lgh::writeDds(image);
    const lgh::BlockCompressedImage read = lgh::readDds(file.data(), file.size(), "t.dds");
    EXPECT_EQ(read.format, image.format);
    EXPECT_EQ(read.srgb, srgb);
    EXPECT_EQ(read.width, 8);
    EXPECT_EQ(read.height, 4);
    EXPECT_EQ(read.levels, image.levels);
  }
  const std::vector<std::uint8_t> file = lgh::writeDds(twoLevelBc1());
  auto error = [](std::vector<std::uint8_t> bytes) {
    return std::string(errorOf([&] { lgh::readDds(bytes.data(), bytes.size(), "t.dds"); }).what());
  };
  EXPECT_NE(error({file.begin(), file.begin() + 60}).find("truncated"), std::string::npos);
  EXPECT_NE(error({file.begin(), file.end() - 1}).find("mip level 3"), std::string::npos);
  std::vector<std::uint8_t> badFourCc = file;
  badFourCc[84] = 'X';
  EXPECT_NE(error(badFourCc).find("FourCC"), std::string::npos);
  std::vector<std::uint8_t> huge = file;
  huge[16] = 0xFF;  // width's high bytes
  huge[17] = 0xFF;
  huge[18] = 0xFF;
  EXPECT_NE(error(huge).find("outside"), std::string::npos);
  std::vector<std::uint8_t> manyLevels = file;
  manyLevels[28] = 30;
  EXPECT_NE(error(manyLevels).find("mip levels"), std::string::npos);
}

// --- glTF: extras.lgh and MSFT_texture_dds -----------------------------------------------------

// A .gltf with one textured quad whose material carries `extras` and whose texture 0 is `image`
// (a PNG-free asset: the image is the DDS file, through MSFT_texture_dds).
lgh::Scene loadQuad(const json& extras, const std::vector<std::uint8_t>& dds) {
  const lgh::test::GltfQuad quad = lgh::test::ddsTexturedQuad("tiles", "tiles.dds", extras);
  const std::map<std::string, std::vector<std::uint8_t>> files = {
      {"quad.gltf", std::vector<std::uint8_t>(quad.gltf.begin(), quad.gltf.end())},
      {"quad.bin", quad.bin},
      {"tiles.dds", dds}};
  return lgh::loadGltfFromMemory("quad.gltf", files);
}

std::vector<std::uint8_t> redBc1Dds() {
  lgh::BlockCompressedImage image;
  image.format = lgh::BlockFormat::Bc1;
  image.width = 4;
  image.height = 4;
  image.levels = {{0x00, 0xF8, 0x1F, 0x00, 0x00, 0x00, 0x00, 0x00}};  // all red
  return lgh::writeDds(image);
}

TEST(GltfMaterialExtras, ApplyTheSameParameters) {
  const lgh::Scene scene = loadQuad({{"lgh",
                                      {{"model", "phong"},
                                       {"shading", "flat"},
                                       {"shininess", 90},
                                       {"surface", "parallax"},
                                       {"height_texture", {{"texture", 0}}},
                                       {"light_map", {{"texture", 0}}},
                                       {"sampling", {{"wrap_s", "clamp-to-border"}}}}}},
                                    redBc1Dds());
  ASSERT_EQ(scene.materials.size(), 1U);
  const lgh::Material& m = scene.materials[0];
  EXPECT_EQ(m.model, lgh::MaterialModel::Phong);
  EXPECT_EQ(m.classic.shading, lgh::ShadingMode::Flat);
  EXPECT_EQ(m.classic.shininess, 90.0F);
  EXPECT_EQ(m.surface.technique, lgh::SurfaceDetail::Parallax);
  EXPECT_TRUE(m.surface.heightTexture.valid());
  EXPECT_EQ(m.lightMap.texCoord, 1);
  EXPECT_EQ(m.baseColorTexture.sampler.wrapS, 0x812D);
  // A height map from extras gets the mesh its tangent frame.
  EXPECT_TRUE(scene.meshes.at(0).primitives.at(0).tangents);
  // The DDS: its blocks kept for the GPU, its texels decoded for the CPU.
  ASSERT_EQ(scene.compressedImages.size(), 1U);
  const int image = m.baseColorTexture.image;
  EXPECT_EQ(scene.compressedImages.at(image).format, lgh::BlockFormat::Bc1);
  EXPECT_EQ(scene.images.at(static_cast<std::size_t>(image)).pixels[0], 255);
  EXPECT_EQ(scene.images.at(static_cast<std::size_t>(image)).pixels[1], 0);
  ASSERT_EQ(scene.textures.size(), 1U);
  EXPECT_EQ(scene.textures[0].image, image);
}

TEST(GltfMaterialExtras, BadExtrasNameTheMaterialAndField) {
  const std::vector<std::pair<json, std::string>> cases = {
      {{{"lgh", {{"shininess", -1}}}}, "/materials/0/extras/lgh/shininess"},
      {{{"lgh", {{"model", "ward"}}}}, "/materials/0/extras/lgh/model"},
      {{{"lgh", {{"light_map", {{"texture", 5}}}}}}, "/materials/0/extras/lgh/light_map/texture"},
      {{{"lgh", {{"shading", "gouraud"}}}}, "/materials/0/extras/lgh/shading"},
  };
  for (const auto& [caseExtras, where] : cases) {
    const json& extras = caseExtras;  // clang 14 (clang-tidy) captures no structured bindings
    SCOPED_TRACE(extras.dump());
    const lgh::Error error = errorOf([&] { loadQuad(extras, redBc1Dds()); });
    EXPECT_EQ(error.code(), lgh::ErrorCode::Invalid);
    const std::string message = error.what();
    EXPECT_NE(message.find("(material 'tiles')"), std::string::npos) << message;
    EXPECT_NE(message.find(where), std::string::npos) << message;
  }
  // Other extras are none of this renderer's business.
  EXPECT_NO_THROW(loadQuad({{"author", "someone"}}, redBc1Dds()));
}

TEST(GltfMaterialExtras, BrokenDdsIsAnErrorNamingTheImage) {
  std::vector<std::uint8_t> dds = redBc1Dds();
  dds.resize(dds.size() - 4);
  const lgh::Error error = errorOf([&] { loadQuad(json::object(), dds); });
  EXPECT_EQ(error.code(), lgh::ErrorCode::Invalid);
  EXPECT_NE(std::string(error.what()).find("tiles.dds"), std::string::npos) << error.what();
}

}  // namespace
