#version 450
// Binned S1, pass 1 of 3: a counting sort of the lights by S1 tile (T^3 S1 cells, lghBinTile()).
// One thread per light adds 1 to its tile's count (one global atomic per light, on a counter
// array small enough for the L2). The last work group to finish (lghFinishLastGroup) scans the
// counts into tile offsets (binStart, tiles + 1 entries) and lists the work of the accumulation:
// one (tile, chunk) item per LGH_BIN_CHUNK lights of every occupied tile, whose count becomes the
// dispatch arguments of lgh_bin_accum.comp (slot LGH_SLOT_BIN_ACCUM). Also clears the auto-level
// bitmaps, as the direct scatter does. The dispatch has at least one group, so an empty build
// still gets zero items.
#define LGH_BUILD_INTERNALS
#define LGH_BINNED
#define LGH_COHERENT
#include "include/lgh_types.glsl"

layout(local_size_x = LGH_GROUP) in;

uniform uint u_clearWords;  // occupancy bitmap words to clear (lgh_occupancy.comp's)

void countLight(uint i) {
  const PointLight light = lights[i];
  if (luminance(light.intensityPad.rgb) <= 0.0) return;
  atomicAdd(binCount[lghBinIndex(lghGridCoordinate(light.positionPad.xyz, 1u))], 1u);
}

uint chunksOf(uint lightCount) { return lghCeilDiv(lightCount, LGH_BIN_CHUNK); }

// The epilogue of the last group: each thread takes LGH_BIN_SCAN_ITEMS consecutive tiles per
// round, so one group scans 4096 tiles per round (one round at 1M lights on the demo scene).
void binOffsets() {
  const uint tid = gl_LocalInvocationID.x;
  const uint tiles = lgh.levelCount > 0u ? st.binTiles.w : 0u;
  uint lightBase = 0u;
  uint itemBase = 0u;
  for (uint round = 0u; round < tiles; round += LGH_GROUP * LGH_BIN_SCAN_ITEMS) {
    const uint first = round + tid * LGH_BIN_SCAN_ITEMS;
    uint counts[LGH_BIN_SCAN_ITEMS];
    uint myLights = 0u;
    uint myItems = 0u;
    for (uint k = 0u; k < LGH_BIN_SCAN_ITEMS; ++k) {
      counts[k] = first + k < tiles ? binCount[first + k] : 0u;
      myLights += counts[k];
      myItems += chunksOf(counts[k]);
    }
    uint roundLights;
    uint roundItems;
    uint lightAt = lightBase + lghGroupExclusiveScan(myLights, roundLights);
    uint itemAt = itemBase + lghGroupExclusiveScan(myItems, roundItems);
    for (uint k = 0u; k < LGH_BIN_SCAN_ITEMS && first + k < tiles; ++k) {
      binStart[first + k] = lightAt;
      lightAt += counts[k];
      for (uint c = 0u; c < chunksOf(counts[k]); ++c) binItems[itemAt++] = uvec2(first + k, c);
    }
    lightBase += roundLights;
    itemBase += roundItems;
  }
  if (tid == 0u) {
    binStart[tiles] = lightBase;
    st.dispatchArgs[LGH_SLOT_BIN_ACCUM] = lghDispatch(itemBase);
  }
}

void main() {
  const uint i = lghGroupIndex() * LGH_GROUP + gl_LocalInvocationID.x;
  // The auto-level bitmaps are done with: clear them here rather than by a separate command.
  const uint threads = gl_NumWorkGroups.x * gl_NumWorkGroups.y * LGH_GROUP;
  for (uint w = i; w < u_clearWords; w += threads) bitmap[w] = 0u;
  if (i < st.lightCount && lgh.levelCount > 0u) countLight(i);
  if (lghFinishLastGroup(3u)) binOffsets();
}
