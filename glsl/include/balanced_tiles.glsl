// The pixel of this invocation in a per-pixel compute pass whose work groups tile the frame, with
// the rows of work groups interleaved: in dispatch order, the first half of the groups covers the
// even rows of tiles and the second half the odd ones. Used by the GL passes and by Vulkan's
// ray-query trace alike (plain GLSL); include it after the work-group size is declared.
//
// Why: a CPU rasteriser's compute thread pool (llvmpipe's, which lavapipe shares) gives each of
// its N threads one contiguous N-th of the work groups in dispatch order, not work as it frees
// up. With rows in frame order, two threads split the frame into a bottom and a top half, and a
// model lying mostly in one half left one thread working while the other idled
// (docs/BENCHMARKS.md). On a GPU the order of groups changes nothing.
//
// A pass may dispatch part of the frame's tiles only (passes/surface_tiles.hpp): the includer then
// defines LGH_FIRST_TILE, the first tile's (column, row), and the dispatch covers the tiles from
// there on.
#ifndef LGH_BALANCED_TILES_GLSL
#define LGH_BALANCED_TILES_GLSL

#ifndef LGH_FIRST_TILE
#define LGH_FIRST_TILE uvec2(0u)
#endif

ivec2 balancedPixel() {
  uint rows = gl_NumWorkGroups.y;
  uint evenRows = (rows + 1u) / 2u;
  uint group = gl_WorkGroupID.y;
  uint tileRow = group < evenRows ? 2u * group : 2u * (group - evenRows) + 1u;
  uvec2 tile = uvec2(gl_WorkGroupID.x, tileRow) + LGH_FIRST_TILE;
  return ivec2(tile * gl_WorkGroupSize.xy + gl_LocalInvocationID.xy);
}

#endif
