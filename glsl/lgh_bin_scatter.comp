#version 450
// Binned S1, pass 2 of 3: every contributing light goes to its tile's range of binLights (tile
// order; within a tile, any order). The slot comes from counting the tile's count back down, so
// the counts end at zero for the next build without a clear. The light is stored with the grid
// coordinate t its tile was chosen by, so lgh_bin_accum.comp places it in that very tile.
// One thread per light (the direct scatter's dispatch slot: no groups without levels).
#define LGH_BUILD_INTERNALS
#define LGH_BINNED
#include "include/lgh_types.glsl"

layout(local_size_x = LGH_GROUP) in;

void main() {
  const uint i = lghGroupIndex() * LGH_GROUP + gl_LocalInvocationID.x;
  if (i >= st.lightCount || lgh.levelCount == 0u) return;
  const PointLight light = lights[i];
  const vec3 rgb = light.intensityPad.rgb;
  const float lum = luminance(rgb);
  if (lum <= 0.0) return;
  const vec3 t = lghGridCoordinate(light.positionPad.xyz, 1u);
  const uint tile = lghBinIndex(t);
  const uint left = atomicAdd(binCount[tile], 0xffffffffu);  // the count before: >= 1
  binLights[binStart[tile] + left - 1u] = LghBinLight(vec4(t, lum), vec4(rgb, 0.0));
}
