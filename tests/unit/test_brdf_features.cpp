// The material models and layers a frame's lighting kernels are compiled for (BrdfFeatures),
// without GL: from the frame's MaterialTable (the scene's materials after the request's overrides)
// and the draw items that use it. Every model and layer a surface of the G-buffer can carry must
// be in the masks, or the specialised kernel would light it with the wrong code.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lgh/request.hpp"
#include "passes/brdf_features.hpp"
#include "passes/material_binding.hpp"
#include "scene/demo_scene.hpp"
#include "scene/material_table.hpp"

namespace {

using json = nlohmann::json;
using lgh::BrdfFeatures;
using lgh::MaterialModel;

// What a GpuScene of `scene` would draw: one item per primitive of every instance.
std::vector<lgh::GpuScene::DrawItem> drawItemsOf(const lgh::Scene& scene) {
  std::vector<lgh::GpuScene::DrawItem> items;
  for (const lgh::MeshInstance& instance : scene.instances) {
    for (const lgh::Primitive& primitive :
         scene.meshes[static_cast<std::size_t>(instance.mesh)].primitives) {
      lgh::GpuScene::DrawItem item{};
      item.material = primitive.material;
      item.topology = primitive.topology;
      items.push_back(item);
    }
  }
  return items;
}

BrdfFeatures featuresOf(const lgh::Scene& scene, const json& materials = json::array()) {
  const lgh::RenderRequest request = lgh::parseRenderRequest(json{{"materials", materials}});
  const lgh::MaterialTable table(scene, request.materials);
  return lgh::brdfFeatures(table, drawItemsOf(scene));
}

// Every model of the demo's row, without lines: all but unlit.
constexpr std::uint32_t kRowModels =
    BrdfFeatures::kAllModels & ~BrdfFeatures::modelBit(MaterialModel::Unlit);
constexpr std::uint32_t kMetallicRoughness =
    BrdfFeatures::modelBit(MaterialModel::MetallicRoughness);

lgh::Scene plainScene() {
  lgh::Scene scene = lgh::makeDemoScene();
  for (lgh::Material& material : scene.materials) material.model = MaterialModel::MetallicRoughness;
  return scene;
}

int materialIndex(const lgh::Scene& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    if (scene.materials[i].name == name) return static_cast<int>(i);
  }
  ADD_FAILURE() << "no material " << name;
  return -1;
}

TEST(BrdfFeatures, DemoSceneHasItsRowOfModelsAndNoLayers) {
  const BrdfFeatures features = featuresOf(lgh::makeDemoScene());
  EXPECT_EQ(features.models, kRowModels);
  EXPECT_EQ(features.layers, 0U);
  EXPECT_FALSE(features.all());
  EXPECT_EQ(features.describe(),
            "metallic-roughness,phong,blinn-phong,oren-nayar,cook-torrance layers:none");
}

TEST(BrdfFeatures, PlainSceneIsMetallicRoughnessOnly) {
  const BrdfFeatures features = featuresOf(plainScene());
  EXPECT_EQ(features.models, kMetallicRoughness);
  EXPECT_EQ(features.layers, 0U);
  EXPECT_EQ(features.defines(), "#define LGH_BRDF_MODELS 1\n#define LGH_BRDF_LAYERS 0\n");
}

TEST(BrdfFeatures, EveryModelAndLayerIsTheGenericKernel) {
  const BrdfFeatures every;
  EXPECT_TRUE(every.all());
  EXPECT_EQ(every.defines(), "");
  EXPECT_EQ(every.describe(), "all");
  BrdfFeatures built = BrdfFeatures::none();
  for (const auto& entry : lgh::EnumNames<MaterialModel>::names) built.add(entry.value, 0U);
  built.add(MaterialModel::MetallicRoughness, BrdfFeatures::kAllLayers);
  EXPECT_EQ(built, every);
}

TEST(BrdfFeatures, RequestOverrideThatSwitchesAModelAddsIt) {
  const lgh::Scene scene = plainScene();
  const BrdfFeatures features = featuresOf(
      scene, json::array({{{"match", {{"name", "white"}}}, {"parameters", {{"model", "phong"}}}},
                          {{"match", {{"index", materialIndex(scene, "red")}}},
                           {"parameters", {{"model", "cook-torrance"}}}}}));
  EXPECT_EQ(features.models, kMetallicRoughness | BrdfFeatures::modelBit(MaterialModel::Phong) |
                                 BrdfFeatures::modelBit(MaterialModel::CookTorrance));
}

TEST(BrdfFeatures, OverrideOfEveryMaterialLeavesOnlyItsModel) {
  // "All" also changes the default material of primitives without one.
  lgh::Scene scene = lgh::makeDemoScene();
  scene.meshes[0].primitives[0].material = -1;
  const BrdfFeatures features = featuresOf(
      scene,
      json::array({{{"match", {{"all", true}}}, {"parameters", {{"model", "oren-nayar"}}}}}));
  EXPECT_EQ(features.models, BrdfFeatures::modelBit(MaterialModel::OrenNayar));
  EXPECT_EQ(features.layers, 0U);
}

TEST(BrdfFeatures, DefaultMaterialCountsWhereAPrimitiveHasNoMaterial) {
  lgh::Scene scene = lgh::makeDemoScene();
  for (lgh::Material& material : scene.materials) material.model = MaterialModel::BlinnPhong;
  EXPECT_EQ(featuresOf(scene).models, BrdfFeatures::modelBit(MaterialModel::BlinnPhong));
  scene.meshes[0].primitives[0].material = -1;
  EXPECT_EQ(featuresOf(scene).models,
            BrdfFeatures::modelBit(MaterialModel::BlinnPhong) | kMetallicRoughness);
}

TEST(BrdfFeatures, LayersOfMetallicRoughnessMaterialsOnly) {
  lgh::Scene scene = plainScene();
  scene.materials[static_cast<std::size_t>(materialIndex(scene, "white"))].clearcoat.factor = 0.5F;
  scene.materials[static_cast<std::size_t>(materialIndex(scene, "red"))].sheen.colorFactor =
      glm::vec3(0.2F);
  lgh::Material& green = scene.materials[static_cast<std::size_t>(materialIndex(scene, "green"))];
  green.transmission.factor = 0.9F;
  green.model = MaterialModel::Phong;  // a classic model's layers are never read
  const BrdfFeatures features = featuresOf(scene);
  EXPECT_EQ(features.layers, lgh::kLayerClearcoat | lgh::kLayerSheen);
  EXPECT_EQ(features.describe(), "metallic-roughness,phong layers:clearcoat,sheen");
  EXPECT_EQ(features.defines(), "#define LGH_BRDF_MODELS 5\n#define LGH_BRDF_LAYERS 3\n");
}

TEST(BrdfFeatures, UnlitDrawItemsAreUnlitWhateverTheirMaterial) {
  // Lines and points without normals: the G-buffer pass shades them unlit.
  const lgh::Scene scene = plainScene();
  lgh::MaterialTable table(scene, {});
  std::vector<lgh::GpuScene::DrawItem> items(1);
  items[0].material = materialIndex(scene, "white");
  items[0].unlit = true;
  const BrdfFeatures features = lgh::brdfFeatures(table, items);
  EXPECT_EQ(features.models, BrdfFeatures::modelBit(MaterialModel::Unlit));
}

TEST(BrdfFeatures, LayerBitsFollowTheMaterial) {
  lgh::Material material;
  EXPECT_EQ(lgh::materialLayerBits(material), 0U);
  material.specular.ior = 1.33F;
  EXPECT_EQ(lgh::materialLayerBits(material), lgh::kLayerSpecular);
  material.transmission.factor = 0.2F;
  EXPECT_EQ(lgh::materialLayerBits(material), lgh::kLayerSpecular | lgh::kLayerTransmission);
}

// The G-buffer pass leaves out the layers and emissive targets of frames that need neither; a
// surface that writes one must be seen, or its pixels would be read from a stale target.
TEST(BrdfFeatures, LayersTargetOnlyForMaterialLayersOrClassicModels) {
  lgh::Scene scene = plainScene();
  EXPECT_FALSE(featuresOf(scene).usesLayersTarget());
  EXPECT_TRUE(featuresOf(lgh::makeDemoScene()).usesLayersTarget());  // its row of classic models
  scene.materials[static_cast<std::size_t>(materialIndex(scene, "white"))].clearcoat.factor = 0.5F;
  EXPECT_TRUE(featuresOf(scene).usesLayersTarget());
  scene = plainScene();
  scene.materials[static_cast<std::size_t>(materialIndex(scene, "red"))].model =
      MaterialModel::OrenNayar;
  EXPECT_TRUE(featuresOf(scene).usesLayersTarget());
}

TEST(BrdfFeatures, EmissionFromAFactorALightMapOrAnUnlitSurface) {
  lgh::Scene scene = plainScene();
  const auto emits = [](const lgh::Scene& s, std::vector<lgh::GpuScene::DrawItem> items) {
    return lgh::surfacesEmit(lgh::MaterialTable(s, {}), items);
  };
  EXPECT_TRUE(emits(scene, drawItemsOf(scene)));  // the demo's ceiling panel
  for (lgh::Material& material : scene.materials) material.emissiveFactor = glm::vec3(0.0F);
  EXPECT_FALSE(emits(scene, drawItemsOf(scene)));
  std::vector<lgh::GpuScene::DrawItem> items = drawItemsOf(scene);
  items[0].unlit = true;
  EXPECT_TRUE(emits(scene, items));
  scene.materials[static_cast<std::size_t>(materialIndex(scene, "white"))].lightMap.image = 0;
  EXPECT_TRUE(emits(scene, drawItemsOf(scene)));
}

// The G-buffer shader is compiled without the code a draw's material cannot need (and without a
// discard, so that its depth test runs first): every feature the material uses must be in its key.
TEST(MaterialFeatures, EachFeatureComesFromWhatTheMaterialUses) {
  lgh::GpuScene::DrawItem item{};
  lgh::Material plain;
  EXPECT_EQ(lgh::materialFeatures(plain, item), 0U);
  lgh::Material masked = plain;
  masked.alphaMode = lgh::AlphaMode::Mask;
  EXPECT_EQ(lgh::materialFeatures(masked, item), lgh::kMaterialDiscard);
  lgh::Material relief = plain;
  relief.surface.technique = lgh::SurfaceDetail::Relief;
  relief.surface.heightTexture.image = 0;
  relief.surface.reliefSilhouettes = true;
  const std::uint32_t frame = lgh::kMaterialSurfaceFrame;
  EXPECT_EQ(lgh::materialFeatures(relief, item),
            lgh::kMaterialDiscard | lgh::kMaterialHeight | frame);
  relief.surface.reliefSilhouettes = false;
  EXPECT_EQ(lgh::materialFeatures(relief, item), lgh::kMaterialHeight | frame);
  lgh::Material coated = plain;
  coated.clearcoat.factor = 0.5F;  // the layers read the tangent frame
  EXPECT_EQ(lgh::materialFeatures(coated, item), lgh::kMaterialLayers | frame);
  lgh::Material phong = coated;  // a classic model's layers are never read
  phong.model = MaterialModel::Phong;
  EXPECT_EQ(lgh::materialFeatures(phong, item), lgh::kMaterialClassic);
  lgh::Material bicubic = plain;
  bicubic.bicubic = true;
  EXPECT_EQ(lgh::materialFeatures(bicubic, item), lgh::kMaterialBicubic);
  // Any texture, in whichever slot, needs the texture coordinates (and may need the tangents).
  const std::size_t textures = lgh::allMaterialTextures(plain).size();
  for (std::size_t i = 0; i < textures; ++i) {
    lgh::Material textured = plain;
    lgh::allMaterialTextures(textured)[i]->image = 0;
    EXPECT_EQ(lgh::materialFeatures(textured, item) & frame, frame) << "texture " << i;
  }
  item.topology = lgh::Topology::Points;  // cut to disks
  EXPECT_EQ(lgh::materialFeatures(plain, item), lgh::kMaterialDiscard);
}

}  // namespace
