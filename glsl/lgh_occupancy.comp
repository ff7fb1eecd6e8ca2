#version 450
// LGH auto levels (the paper, Sec. 4.2: the largest L with |S1| < N/2), exact, without building S1
// for every candidate. One bit per S1 vertex of every candidate L <= fitLevels (the finest
// candidate, L_f, has the finest S1 grid):
//  MARK (default)  per light: set the bits of the L_f vertices the light gives a non-zero trilinear
//                  weight (test-and-test-and-set, counting new bits: |S1(L_f)|).
//  LGH_OCC_STEP    one pyramid step (one thread per vertex of candidate L = L_f - 1 - u_step): V is
//                  occupied iff one of the 27 vertices 2V + {-1,0,1}^3 of candidate L+1 is. Exact:
//                  a light gives V a non-zero weight iff its coordinate t_L lies strictly within 1
//                  of V per axis; t_L = t_(L+1) / 2 exactly, so t_(L+1) lies within 2 of 2V, and
//                  the vertices it marked at L+1 (floor and ceil of t_(L+1)) include one within 1;
//                  conversely such a marked vertex proves such a light.
// Candidates of <= LGH_TAIL_VERTICES vertices are built by the last work group of the last needed
// dispatch (the "tail"), which then chooses L and writes the level table and the dispatch
// arguments of the rest of the build (lghConfigure). Marking every candidate directly instead
// was slow at 1M lights: all threads in flight race for the coarse candidates' few words. Counts go to lgh.candidateS1[L - 1] (kept for reports and tests). The S1 step clears the
// bitmaps afterwards (lgh_scatter.comp, or lgh_bin_count.comp for the binned S1).
#define LGH_BUILD_INTERNALS
#include "include/lgh_types.glsl"

// The tail reads bits that other groups of its dispatch and its own threads wrote: it goes through
// this coherent alias; the marking and the steps keep the cached loads.
layout(std430, binding = LGH_BIND_BUILD_BITMAPS) coherent buffer LghBitmapsCoherent { uint bitmapCoherent[]; };

layout(local_size_x = LGH_GROUP) in;

uniform uint u_count;  // MARK: lights
uniform uint u_step;   // STEP: candidate L_f - 1 - u_step

shared uint s_words[LGH_GROUP / 32];
shared uint s_count;

bool bitSet(uint L, uint bit, bool inTail) {
  const uint word = st.candBitmap[L - 1u].x + (bit >> 5);
  return (((inTail ? bitmapCoherent[word] : bitmap[word]) >> (bit & 31u)) & 1u) != 0u;
}

uint markVertex(uint word, uint mask) {
  if ((bitmap[word] & mask) != 0u) return 0u;
  return (atomicOr(bitmap[word], mask) & mask) == 0u ? 1u : 0u;
}

uint markLight(uint i) {
  PointLight light = lights[i];
  if (luminance(light.intensityPad.rgb) <= 0.0) return 0u;
  const uint L = st.fineLevel;
  const uvec4 dims = st.candDims[L - 1u];
  const float cells = float(1u << (L - 1u));
  precise vec3 t = min((light.positionPad.xyz - lgh.originH1.xyz) * (st.extentInvTop.w * cells), vec3(cells));
  const vec3 i0 = floor(t);
  const vec3 f = t - i0;
  uint added = 0u;
  for (uint corner = 0u; corner < 8u; ++corner) {
    bvec3 high = bvec3((corner & 1u) != 0u, (corner & 2u) != 0u, (corner & 4u) != 0u);
    if ((high.x && f.x == 0.0) || (high.y && f.y == 0.0) || (high.z && f.z == 0.0)) continue;
    uint bit = lghEncode(uvec3(i0) + uvec3(high), dims.xyz);
    added += markVertex(st.candBitmap[L - 1u].x + (bit >> 5), 1u << (bit & 31u));
  }
  return added;
}

// Candidate L's vertex v from candidate L + 1.
bool coarseOccupied(uint L, uint v, bool inTail) {
  const uvec3 dims = st.candDims[L - 1u].xyz;
  const ivec3 fineDims = ivec3(st.candDims[L].xyz);
  const ivec3 center = ivec3(2u * lghDecode(v, dims));
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 f = center + ivec3(dx, dy, dz);
        if (any(lessThan(f, ivec3(0))) || any(greaterThanEqual(f, fineDims))) continue;
        if (bitSet(L + 1u, lghEncode(uvec3(f), uvec3(fineDims)), inTail)) return true;
      }
    }
  }
  return false;
}

// 256 vertices of candidate L from `first` (a multiple of 256): 8 whole words; counts into s_count.
void produceChunk(uint L, uint first, bool inTail) {
  const uint tid = gl_LocalInvocationID.x;
  if (tid < LGH_GROUP / 32u) s_words[tid] = 0u;
  barrier();
  uint v = first + tid;
  if (v < st.candDims[L - 1u].w && coarseOccupied(L, v, inTail)) {
    atomicOr(s_words[tid >> 5], 1u << (tid & 31u));
  }
  barrier();
  if (tid < LGH_GROUP / 32u) {
    uint word = s_words[tid];
    const uint at = st.candBitmap[L - 1u].x + first / 32u + tid;
    if (inTail) {
      bitmapCoherent[at] = word;
    } else {
      bitmap[at] = word;
    }
    atomicAdd(s_count, uint(bitCount(word)));
  }
  barrier();
}

// candidateS1 was added to atomically by other groups: read it atomically (coherently) too.
uint chooseLevels() {
  const uint contributing = lgh.contributingCount;
  for (uint L = st.fineLevel; L >= 1u; --L) {
    if (2u * atomicAdd(lgh.candidateS1[L - 1u], 0u) < contributing) return L;
  }
  return 1u;
}

// The last group of the last needed dispatch: the small candidates, the choice, the set-up.
void tail() {
  const uint tid = gl_LocalInvocationID.x;
  for (uint L = st.tailFrom; L >= 1u; --L) {
    if (tid == 0u) s_count = 0u;
    barrier();
    for (uint first = 0u; first < st.candDims[L - 1u].w; first += LGH_GROUP) produceChunk(L, first, true);
    memoryBarrierBuffer();
    barrier();
    if (tid == 0u) atomicExchange(lgh.candidateS1[L - 1u], s_count);
  }
  memoryBarrierBuffer();
  barrier();
  if (tid == 0u) lghConfigure(chooseLevels());
}

void main() {
  const uint tid = gl_LocalInvocationID.x;
  if (tid == 0u) s_count = 0u;
  barrier();
#ifdef LGH_OCC_STEP
  const uint L = st.fineLevel - 1u - u_step;
  const uint first = lghGroupIndex() * LGH_GROUP;
  if (first < st.candDims[L - 1u].w) produceChunk(L, first, false);
  if (tid == 0u && s_count > 0u) atomicAdd(lgh.candidateS1[L - 1u], s_count);
  const bool runsTail = u_step + 1u == st.bigSteps;
#else
  const uint i = lghGroupIndex() * LGH_GROUP + tid;
  uint added = (st.fineLevel > 0u && i < u_count) ? markLight(i) : 0u;
  if (added > 0u) atomicAdd(s_count, added);
  barrier();
  if (tid == 0u && s_count > 0u) atomicAdd(lgh.candidateS1[st.fineLevel - 1u], s_count);
  const bool runsTail = st.fineLevel > 0u && st.bigSteps == 0u;
#endif
  if (lghFinishLastGroup(1u) && runsTail) tail();
}
