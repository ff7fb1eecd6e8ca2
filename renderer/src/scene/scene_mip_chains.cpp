#include "scene/scene_mip_chains.hpp"

#include "scene/blit_mip_chain.hpp"

namespace lgh {

SceneMipChains buildSceneMipChains(const Scene& scene) {
  SceneMipChains chains;
  for (const auto& [image, usage] : sampledRgba8Images(scene)) {
    const bool srgb = usage == TextureUsage::Color;
    auto [chain, added] = chains.try_emplace({image, srgb});
    if (!added) continue;  // read with the same encoding by another slot
    chain->second = buildBlitMipChain(*scene.rgba8Image(image), srgb);
  }
  return chains;
}

}  // namespace lgh
