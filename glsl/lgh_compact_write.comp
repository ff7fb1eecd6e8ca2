#version 450
// LGH stream compaction, pass 3 of 3: every occupied dense vertex of a block becomes a GridLight
// at its block's offset plus its rank within the block (vertex order is kept: S1 stays sorted by
// vertex, which the gather relies on). Grid lights go straight into the merged output buffer. The
// pass also clears the accumulators and touched bits it consumed, so the next build starts from
// zero without a full clear, and never reads an untouched vertex's accumulators. For S1 before
// the gather (u_writeS1) it also writes the S1 records and s1Rank[v]: the number of occupied S1
// vertices before v, which locates any x-row of S1 in the records.
//
// From the accumulators (u in cell units, W = luminance(rgb)):
//   centre = origin + (vertex + m1) * h,  m1 = sum(w I u) / W
//   variance = (sum(w I (u^2 + var/h^2)) / W - m1^2) * h^2, clamped at 0.
#define LGH_BUILD_INTERNALS
#include "include/lgh_types.glsl"

layout(local_size_x = LGH_GROUP) in;

uniform uint u_slot;
uniform uint u_firstLevel;
uniform uint u_writeS1;   // 1: also S1 records and ranks
uniform uint u_capacity;  // grid lights the output (and record) buffers hold

void emit(uint outIndex, uint d, uint l, LghLevel level) {
  const uint local = d - level.denseOffset;
  const uvec3 v = lghDecode(local, level.dims.xyz);
  const vec3 rgb = lghReadRgb(d);
  const float lum = luminance(rgb);
  const uint base = d * 9u;
  vec3 m1 = vec3(lghRead(base + 3u), lghRead(base + 4u), lghRead(base + 5u)) / lum;
  vec3 m2 = vec3(lghRead(base + 6u), lghRead(base + 7u), lghRead(base + 8u)) / lum;
  m1 = clamp(m1, vec3(-1.0), vec3(1.0));
  const vec3 varCells = max(m2 - m1 * m1, vec3(0.0));
  const float h = level.cell.x;
  GridLight light;
  light.center = lgh.originH1.xyz + (vec3(v) + m1) * h;
  light.level = l;
  light.intensity = rgb;
  light.vertex = local;
  light.variance = varCells * (h * h);
  light.luminance = lum;
  gridLights[outIndex] = light;
  if (u_writeS1 != 0u) {
    s1Records[outIndex] = LghS1Record(vec4(m1, lum), vec4(rgb, float(v.x)), vec4(varCells, 0.0));
  }
}

void main() {
  const uint g = lghGroupIndex();
  if (g >= st.dispatchArgs[u_slot].w) return;
  const uint tid = gl_LocalInvocationID.x;
  const uint block = st.blocks[u_firstLevel - 1u].x + g;
  const uint l = lghLevelOfDense(block * LGH_BLOCK);
  const LghLevel level = lgh.level[l - 1u];
  const uint end = level.denseOffset + level.dims.w;
  const uint first = block * LGH_BLOCK + tid * 4u;
  // This thread's 4 touched bits, read before the scan: a neighbour clears the word after it.
  const uint touchedBits = (touched[first >> 5] >> (first & 31u)) & 0xfu;
  uint flags = 0u;
  for (uint k = 0u; k < 4u; ++k) {
    uint d = first + k;
    if (d < end && (touchedBits & (1u << k)) != 0u && luminance(lghReadRgb(d)) > 0.0) flags |= 1u << k;
  }
  uint total;
  uint outIndex = blockData[block] + lghGroupExclusiveScan(uint(bitCount(flags)), total);
  for (uint k = 0u; k < 4u; ++k) {
    uint d = first + k;
    if (d >= end) break;
    if (u_writeS1 != 0u) s1Rank[d - level.denseOffset] = outIndex;
    if ((flags & (1u << k)) != 0u) {
      if (outIndex < u_capacity) emit(outIndex, d, l, level);
      ++outIndex;
    }
    if ((touchedBits & (1u << k)) != 0u) lghClear(d);
  }
  // Every thread has read its bits (the scan's barriers lie between); 8 threads share a word.
  if ((tid & 7u) == 0u) touched[first >> 5] = 0u;
}
