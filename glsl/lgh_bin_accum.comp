#version 450
// Binned S1, pass 3 of 3: one work group per (tile, chunk of up to LGH_BIN_CHUNK lights). The
// group adds its lights' trilinear shares to the tile's (T+1)^3 vertices in shared memory (8
// threads per light, one per corner), then adds every touched vertex's 9 sums to the dense
// accumulators with one global atomic each (two 32-bit words with fixed point) and sets its
// touched bit. Neighbouring tiles share their border vertices, and big tiles have several chunks:
// hence atomics for the flush too, but about one per vertex and chunk instead of one per light
// and corner (72 per light), and along the tile's rows instead of at random addresses.
//
// Float atomics: the shared sums are floats (rounding as with float atomics, in another order).
// Fixed point: the shared sums are the same 64-bit two's complement integers as the global ones
// (lghFixedSplit, two 32-bit words with the carry), so every sum is exact and the result is
// bit-identical to the direct scatter's.
#define LGH_BUILD_INTERNALS
#define LGH_BINNED
#include "include/lgh_types.glsl"

layout(local_size_x = LGH_GROUP) in;

#ifdef LGH_FLOAT_ATOMICS
#define TILE LGH_BIN_TILE_FLOAT
#define WORDS 9u  // shared words per vertex
#else
#define TILE LGH_BIN_TILE_FIXED
#define WORDS 18u  // 9 low words, then 9 high words
#endif
#define SIDE (TILE + 1u)
#define TILE_VERTICES (SIDE * SIDE * SIDE)

// Value k of tile vertex v at [k * TILE_VERTICES + v] (high words from 9 * TILE_VERTICES on):
// a light's 8 corners fall in different banks.
#ifdef LGH_FLOAT_ATOMICS
shared float s_acc[WORDS * TILE_VERTICES];
#else
shared uint s_acc[WORDS * TILE_VERTICES];
#endif
shared uint s_touched[(TILE_VERTICES + 31u) / 32u];

void clearTile() {
  for (uint s = gl_LocalInvocationID.x; s < WORDS * TILE_VERTICES; s += LGH_GROUP) {
#ifdef LGH_FLOAT_ATOMICS
    s_acc[s] = 0.0;
#else
    s_acc[s] = 0u;
#endif
  }
  for (uint s = gl_LocalInvocationID.x; s < (TILE_VERTICES + 31u) / 32u; s += LGH_GROUP) {
    s_touched[s] = 0u;
  }
}

void addShared(uint k, uint v, float value) {
#ifdef LGH_FLOAT_ATOMICS
  if (value != 0.0) atomicAdd(s_acc[k * TILE_VERTICES + v], value);
#else
  const uvec2 x = lghFixedSplit(value);
  if (x == uvec2(0u)) return;
  const uint old = atomicAdd(s_acc[k * TILE_VERTICES + v], x.x);
  const uint hi = x.y + ((old + x.x < old) ? 1u : 0u);
  if (hi != 0u) atomicAdd(s_acc[(9u + k) * TILE_VERTICES + v], hi);
#endif
}

void addCorner(LghBinLight light, uint corner, uvec3 tileOrigin) {
  uvec3 vertex;
  vec3 wRgb, moment1, moment2;
  if (!lghCornerShare(light.tLum.xyz, light.rgbPad.rgb, light.tLum.w, corner, vertex, wRgb,
                      moment1, moment2)) {
    return;
  }
  // Always inside: the light was binned by this t (lghBinIndex); the guard keeps a broken
  // invariant from writing outside the shared arrays.
  const uvec3 local = vertex - tileOrigin;
  if (any(greaterThan(local, uvec3(TILE)))) return;
  const uint v = local.x + SIDE * (local.y + SIDE * local.z);
  for (uint k = 0u; k < 3u; ++k) {
    addShared(k, v, wRgb[k]);
    addShared(3u + k, v, moment1[k]);
    addShared(6u + k, v, moment2[k]);
  }
  const uint bit = 1u << (v & 31u);
  if ((s_touched[v >> 5] & bit) == 0u) atomicOr(s_touched[v >> 5], bit);
}

// Slots in (vertex, value) order: consecutive threads add to consecutive accumulator words.
void flush(uvec3 tileOrigin) {
  const LghLevel level = lgh.level[0];
  for (uint s = gl_LocalInvocationID.x; s < 9u * TILE_VERTICES; s += LGH_GROUP) {
    const uint v = s / 9u;
    const uint k = s - 9u * v;
    if ((s_touched[v >> 5] & (1u << (v & 31u))) == 0u) continue;
    const uvec3 local = uvec3(v % SIDE, (v / SIDE) % SIDE, v / (SIDE * SIDE));
    const uint vertex = level.denseOffset + lghEncode(tileOrigin + local, level.dims.xyz);
#ifdef LGH_FLOAT_ATOMICS
    lghAdd(vertex * 9u + k, s_acc[k * TILE_VERTICES + v]);
#else
    lghAddFixed(vertex * 9u + k,
                uvec2(s_acc[k * TILE_VERTICES + v], s_acc[(9u + k) * TILE_VERTICES + v]));
#endif
    if (k == 0u) lghTouch(vertex);
  }
}

void main() {
  const uint item = lghGroupIndex();
  if (item >= st.dispatchArgs[LGH_SLOT_BIN_ACCUM].w) return;  // the whole group
  const uvec2 work = binItems[item];
  const uint begin = binStart[work.x] + work.y * LGH_BIN_CHUNK;
  const uint end = min(begin + LGH_BIN_CHUNK, binStart[work.x + 1u]);
  const uvec3 tileOrigin = lghDecode(work.x, st.binTiles.xyz) * TILE;
  clearTile();
  barrier();
  const uint corner = gl_LocalInvocationID.x & 7u;
  for (uint j = begin + gl_LocalInvocationID.x / 8u; j < end; j += LGH_GROUP / 8u) {
    addCorner(binLights[j], corner, tileOrigin);
  }
  barrier();
  flush(tileOrigin);
}
