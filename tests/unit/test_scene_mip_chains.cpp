// The mip chains a CPU rasteriser's upload takes from the prefetch thread
// (scene/scene_mip_chains.hpp): one per image and colour encoding the materials sample it with,
// sRGB for colour slots and linear for the rest, none for images that arrived block-compressed or
// are not RGBA8, each the chain the upload would have built itself (buildBlitMipChain).
#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "scene/blit_mip_chain.hpp"
#include "scene/scene_mip_chains.hpp"

namespace {

lgh::Image8 gradient(int width, int height, int channels = 4) {
  lgh::Image8 image;
  image.width = width;
  image.height = height;
  image.channels = channels;
  for (int i = 0; i < width * height * channels; ++i) {
    image.pixels.push_back(static_cast<std::uint8_t>((i * 37) % 251));
  }
  return image;
}

bool sameLevels(const std::vector<lgh::Image8>& a, const std::vector<lgh::Image8>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].width != b[i].width || a[i].height != b[i].height || a[i].pixels != b[i].pixels) {
      return false;
    }
  }
  return true;
}

TEST(SceneMipChains, OnePerImageAndEncodingTheMaterialsSample) {
  lgh::Scene scene;
  scene.images = {gradient(8, 6), gradient(4, 4), gradient(4, 4, 3), gradient(5, 3)};
  scene.compressedImages.emplace(1, lgh::BlockCompressedImage{});  // arrived as blocks
  lgh::Material material;
  material.baseColorTexture.image = 0;          // colour: sRGB
  material.metallicRoughnessTexture.image = 0;  // the same image as data: linear
  material.normalTexture.image = 1;             // block-compressed: no chain
  material.occlusionTexture.image = 2;          // three channels: not uploaded as RGBA8
  material.emissiveTexture.image = 7;           // no such image
  scene.materials.push_back(material);
  lgh::Material second;
  second.lightMap.image = 3;          // colour
  second.baseColorTexture.image = 0;  // a chain already built: not built again
  scene.materials.push_back(second);

  const lgh::SceneMipChains chains = lgh::buildSceneMipChains(scene);
  ASSERT_EQ(chains.size(), 3U);
  EXPECT_TRUE(sameLevels(chains.at({0, true}), lgh::buildBlitMipChain(scene.images[0], true)));
  EXPECT_TRUE(sameLevels(chains.at({0, false}), lgh::buildBlitMipChain(scene.images[0], false)));
  EXPECT_TRUE(sameLevels(chains.at({3, true}), lgh::buildBlitMipChain(scene.images[3], true)));
  EXPECT_FALSE(sameLevels(chains.at({0, true}), chains.at({0, false})));  // the encodings differ
}

}  // namespace
