#version 450
// LGH stream compaction, pass 1 of 2: occupied vertices (touched, luminance of the accumulated
// rgb > 0) per block of LGH_BLOCK dense vertices; untouched ones cost a shared bitmap word. Blocks
// never straddle levels (each level's dense range is block aligned). The last work group then
// scans the block counts of the range, in place, starting at the range's output base (0 for S1 or
// for all levels; |S1| for levels 2..L of the gather method, which compacts S1 first), and writes
// each level's offset and count into the level table; the final compaction also writes the total
// and the indirect draw commands. Output beyond the grid-light capacity is dropped and flagged
// (lgh.overflow). The dispatch has at least one group, so an empty range still gets its table.
#define LGH_BUILD_INTERNALS
#define LGH_COHERENT
#include "include/lgh_types.glsl"

layout(local_size_x = LGH_GROUP) in;

uniform uint u_slot;         // dispatch slot: w = blocks in the range
uniform uint u_firstLevel;   // the range starts at this level's first block
uniform uint u_onlyFirst;    // 1: the range is u_firstLevel alone (S1 before the gather)
uniform uint u_final;        // 1: last compaction of the build (total, draw commands)
uniform uint u_capacity;     // grid lights the output buffer holds
uniform uint u_startLevel;   // lowest level of the LGH_DRAW_FROM_START / BELOW_TOP commands
uniform uint u_vertexCount;  // vertices per instance (the light volume's mesh)

shared uint s_count;

void countBlock(uint block) {
  const uint tid = gl_LocalInvocationID.x;
  const LghLevel level = lgh.level[lghLevelOfDense(block * LGH_BLOCK) - 1u];
  const uint end = level.denseOffset + level.dims.w;
  const uint first = block * LGH_BLOCK + tid * 4u;
  uint occupied = 0u;
  for (uint k = 0u; k < 4u; ++k) {
    uint d = first + k;
    if (d < end && lghOccupied(d)) ++occupied;
  }
  if (occupied > 0u) atomicAdd(s_count, occupied);
  barrier();
  if (tid == 0u) blockData[block] = s_count;
}

uint scanBlocks(uint blockBegin, uint blockEnd, uint base) {
  const uint tid = gl_LocalInvocationID.x;
  uint running = base;
  for (uint chunk = blockBegin; chunk < blockEnd; chunk += LGH_GROUP) {
    uint b = chunk + tid;
    uint count = b < blockEnd ? blockData[b] : 0u;
    uint total;
    uint exclusive = lghGroupExclusiveScan(count, total);
    if (b < blockEnd) blockData[b] = running + exclusive;
    running += total;
  }
  return running;
}

void writeLevels(uint firstLevel, uint lastLevel, uint end) {
  for (uint l = firstLevel; l <= lastLevel; ++l) {
    uint offset = blockData[st.blocks[l - 1u].x];
    uint next = l < lastLevel ? blockData[st.blocks[l].x] : end;
    lgh.level[l - 1u].offset = min(offset, u_capacity);
    lgh.level[l - 1u].count = min(next, u_capacity) - min(offset, u_capacity);
  }
}

void writeDraws(uint L) {
  for (uint i = 0u; i < LGH_DRAW_COMMANDS; ++i) draws[i] = uvec4(u_vertexCount, 0u, 0u, 0u);
  for (uint l = 1u; l <= L; ++l) {
    draws[l] = uvec4(u_vertexCount, lgh.level[l - 1u].count, 0u, lgh.level[l - 1u].offset);
  }
  uint start = max(u_startLevel, 1u);
  if (start > L) return;
  uint offset = lgh.level[start - 1u].offset;
  uint below = 0u;
  for (uint l = start; l < L; ++l) below += lgh.level[l - 1u].count;
  draws[LGH_DRAW_FROM_START] = uvec4(u_vertexCount, below + lgh.level[L - 1u].count, 0u, offset);
  draws[LGH_DRAW_BELOW_TOP] = uvec4(u_vertexCount, below, 0u, offset);
}

// The epilogue of the last group: offsets, level table, draws.
void offsets() {
  const uint L = lgh.levelCount;
  const uint lastLevel = u_onlyFirst != 0u ? u_firstLevel : L;
  const bool any = L > 0u && u_firstLevel <= L;
  const uint base = (u_firstLevel == 1u || L == 0u) ? 0u : lgh.level[0].count;
  uint end = base;
  if (any) {
    const uint blockBegin = st.blocks[u_firstLevel - 1u].x;
    const uint blockEnd = st.blocks[lastLevel - 1u].x + st.blocks[lastLevel - 1u].y;
    end = scanBlocks(blockBegin, blockEnd, base);
    memoryBarrierBuffer();
    barrier();
  }
  if (gl_LocalInvocationID.x != 0u) return;
  if (any) writeLevels(u_firstLevel, lastLevel, end);
  if (end > u_capacity) lgh.overflow = 1u;
  if (any && u_onlyFirst != 0u && u_firstLevel == 1u) s1Rank[lgh.level[0].dims.w] = end;
  if (u_final != 0u) {
    lgh.totalLights = min(end, u_capacity);
    writeDraws(L);
  }
}

void main() {
  if (gl_LocalInvocationID.x == 0u) s_count = 0u;
  barrier();
  const uint g = lghGroupIndex();
  if (g < st.dispatchArgs[u_slot].w) countBlock(st.blocks[u_firstLevel - 1u].x + g);
  if (lghFinishLastGroup(2u)) offsets();
}
