#include "scene/scene_mip_chains.hpp"

#include "scene/blit_mip_chain.hpp"

namespace lgh {

SceneMipChains buildSceneMipChains(const Scene& scene) {
  SceneMipChains chains;
  for (const Material& material : scene.materials) {
    for (const MaterialTextureSlot& slot : materialTextureSlots(material)) {
      const int image = slot.texture->image;
      if (image < 0 || static_cast<std::size_t>(image) >= scene.images.size()) continue;
      const Image8& pixels = scene.images[static_cast<std::size_t>(image)];
      if (pixels.width <= 0 || pixels.height <= 0 || pixels.channels != 4) continue;
      if (scene.compressedImages.count(image) != 0) continue;
      const bool srgb = slot.usage == TextureUsage::Color;
      auto [chain, added] = chains.try_emplace({image, srgb});
      if (added) chain->second = buildBlitMipChain(pixels, srgb);
    }
  }
  return chains;
}

}  // namespace lgh
