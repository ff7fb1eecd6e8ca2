#version 450 core
// Interleaved sampling, draw commands of the raster path: tile t (of n^2) draws the lights
// j = t, t + n^2, ... of the levels below the top (j counted from the start level's first light),
// as instances of the light-volume cube. Counts come from the level table, on the GPU.
// Inputs: level table. Output: DrawArraysIndirectCommand[n^2].

#include "include/lgh_shading.glsl"

layout(local_size_x = 16) in;

layout(std430, binding = LGH_BIND_TILE_DRAWS) writeonly buffer LghTileDraws { uvec4 draws[]; };

uniform uint uVertexCount;

void main() {
  uint tile = gl_LocalInvocationID.x;
  uint tiles = uint(uInterleave * uInterleave);
  if (tile >= tiles) return;
  LghFrame frame = lghFrame();
  uint lights = 0u;
  if (lghHasLights(frame)) lights = lghTopOffset(frame) - lghFirstLight(frame);
  uint instances = lights > tile ? (lights - tile + tiles - 1u) / tiles : 0u;
  draws[tile] = uvec4(uVertexCount, instances, 0u, 0u);
}
