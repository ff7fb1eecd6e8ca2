// The CPU-built mip chains of a scene's textures, made where the scene is prepared (a prefetch
// thread) rather than when the render thread uploads it: on a CPU rasteriser
// (TextureCapabilities::mipmapsOnCpu) GpuScene uploads these levels instead of building them
// itself (docs/BENCHMARKS.md). Plain CPU data, no GL.
#pragma once

#include <map>
#include <utility>
#include <vector>

#include "lgh/image.hpp"
#include "scene/scene.hpp"

namespace lgh {

// By (index into Scene::images, sRGB): the levels below level 0 (scene/blit_mip_chain.hpp).
using SceneMipChains = std::map<std::pair<int, bool>, std::vector<Image8>>;

// The chains of the images the scene's materials sample as uncompressed RGBA8, each with the
// colour encoding its slot reads it with (colour slots sRGB, the rest linear), as GpuScene's
// upload without texture compression picks them. Images that arrived block-compressed have none.
SceneMipChains buildSceneMipChains(const Scene& scene);

}  // namespace lgh
