#version 450
// LGH gather (the paper's Sec. 3.1): level l >= 2 built from the compacted S1 grid lights, each
// taken as a point light at its illumination centre with level-l trilinear weights. A level-l
// vertex V (S1 index K = 2^(l-1) V) can only receive S1 lights of the S1 vertices within
// s = 2^(l-1) of K per axis (a centre lies within one S1 cell of its vertex), so it walks the
// (2s+1)^2 x-rows of that box; s1Rank turns a row's x-range into a range of compacted records
// (S1 is compacted in vertex order), so empty vertices cost nothing but the two rank reads.
// All arithmetic is in S1 cell units relative to V: u = (x_S1 - K + offset) / s, exact scaling.
// Variance combines as a mixture: each S1 light brings its own variance plus its offset^2.
//
// Levels whose box is small run one thread per vertex; the others one work group per (vertex,
// chunk of rows) with a shared-memory reduction and one atomic add per chunk. All levels can run
// in one dispatch (u_level = 0): they only read S1.
#define LGH_BUILD_INTERNALS
#include "include/lgh_types.glsl"

layout(local_size_x = LGH_GROUP) in;

uniform uint u_level;  // 0: every level >= 2 (slot LGH_SLOT_GATHER_ALL); else that level only

shared float s_sum[9][LGH_GROUP];

struct Sums {
  vec3 rgb;
  vec3 m1;
  vec3 m2;
};

void gatherRow(inout Sums sums, uvec3 d1, ivec3 k, uint y, uint z, uint x0, uint x1, float invS) {
  const uint rowBase = d1.x * (y + d1.y * z);
  const uint begin = s1Rank[rowBase + x0];
  const uint end = s1Rank[rowBase + x1 + 1u];
  const vec2 dyz = vec2(float(int(y) - k.y), float(int(z) - k.z));
  const float invS2 = invS * invS;
  for (uint j = begin; j < end; ++j) {
    const LghS1Record r = s1Records[j];
    const float dx = r.rgbX.w - float(k.x);
    const vec3 u = (vec3(dx, dyz) + r.offsetLum.xyz) * invS;
    const vec3 axis = 1.0 - abs(u);
    if (any(lessThanEqual(axis, vec3(0.0)))) continue;
    const float w = axis.x * axis.y * axis.z;
    const float wi = w * r.offsetLum.w;
    sums.rgb += w * r.rgbX.rgb;
    sums.m1 += wi * u;
    sums.m2 += wi * (u * u + r.varPad.xyz * invS2);
  }
}

struct Box {
  ivec3 k;  // the vertex in S1 indices
  uvec3 lo;
  uvec3 hi;
};

Box supportBox(uint vertex, uint l, LghLevel level, uvec3 d1) {
  const int s = 1 << (l - 1u);
  Box box;
  box.k = ivec3(lghDecode(vertex, level.dims.xyz)) * s;
  box.lo = uvec3(max(box.k - s, ivec3(0)));
  box.hi = uvec3(min(box.k + s, ivec3(d1) - 1));
  return box;
}

void accumulate(uint l, LghLevel level, uint vertex, Sums sums) {
  if (luminance(sums.rgb) > 0.0) lghAccumulate(level.denseOffset + vertex, sums.rgb, sums.m1, sums.m2);
}

void gatherThread(uint l, LghLevel level, uint item) {
  const uint vertex = item * LGH_GROUP + gl_LocalInvocationID.x;
  if (vertex >= level.dims.w) return;
  const uvec3 d1 = lgh.level[0].dims.xyz;
  const Box box = supportBox(vertex, l, level, d1);
  const float invS = 1.0 / float(1u << (l - 1u));
  Sums sums = Sums(vec3(0.0), vec3(0.0), vec3(0.0));
  for (uint z = box.lo.z; z <= box.hi.z; ++z) {
    for (uint y = box.lo.y; y <= box.hi.y; ++y) {
      gatherRow(sums, d1, box.k, y, z, box.lo.x, box.hi.x, invS);
    }
  }
  accumulate(l, level, vertex, sums);
}

// Work-group sum of `sums` into thread 0's `sums` (two barriers: 16 segments of 16, then the
// 16 segment sums).
void reduceShared(inout Sums sums) {
  const uint tid = gl_LocalInvocationID.x;
  for (int c = 0; c < 3; ++c) {
    s_sum[c][tid] = sums.rgb[c];
    s_sum[3 + c][tid] = sums.m1[c];
    s_sum[6 + c][tid] = sums.m2[c];
  }
  barrier();
  if (tid < LGH_GROUP / 16u) {
    for (int q = 0; q < 9; ++q) {
      float sum = 0.0;
      for (uint i = 0u; i < 16u; ++i) sum += s_sum[q][tid * 16u + i];
      s_sum[q][tid * 16u] = sum;
    }
  }
  barrier();
  if (tid != 0u) return;  // only thread 0 adds the result
  float total[9];
  for (int q = 0; q < 9; ++q) {
    total[q] = 0.0;
    for (uint i = 0u; i < 16u; ++i) total[q] += s_sum[q][i * 16u];
  }
  sums = Sums(vec3(total[0], total[1], total[2]), vec3(total[3], total[4], total[5]),
              vec3(total[6], total[7], total[8]));
}

void gatherGroup(uint l, LghLevel level, uvec4 work, uint item) {
  const uint vertex = item / work.z;
  const uint chunk = item - vertex * work.z;
  const uvec3 d1 = lgh.level[0].dims.xyz;
  const Box box = supportBox(vertex, l, level, d1);
  const uint by = work.w & 0xffffu;
  const uint rows = by * (work.w >> 16);
  const float invS = 1.0 / float(1u << (l - 1u));
  Sums sums = Sums(vec3(0.0), vec3(0.0), vec3(0.0));
  for (uint m = 0u; m < LGH_ROWS_PER_CHUNK / LGH_GROUP; ++m) {
    const uint r = chunk * LGH_ROWS_PER_CHUNK + m * LGH_GROUP + gl_LocalInvocationID.x;
    if (r >= rows) break;
    const uint y = box.lo.y + r % by;
    const uint z = box.lo.z + r / by;
    if (y <= box.hi.y && z <= box.hi.z) gatherRow(sums, d1, box.k, y, z, box.lo.x, box.hi.x, invS);
  }
  reduceShared(sums);
  if (gl_LocalInvocationID.x == 0u) accumulate(l, level, vertex, sums);
}

void main() {
  uint g = lghGroupIndex();
  uint l = u_level;
  if (l == 0u) {
    if (g >= st.dispatchArgs[LGH_SLOT_GATHER_ALL].w) return;
    for (l = 2u; l < lgh.levelCount; ++l) {
      if (g < st.gather[l - 1u].x + st.gather[l - 1u].y) break;
    }
  } else {
    if (l > lgh.levelCount || g >= st.gather[l - 1u].y) return;
    g += st.gather[l - 1u].x;
  }
  const uvec4 work = st.gather[l - 1u];
  const LghLevel level = lgh.level[l - 1u];
  if (work.z == 0u) {
    gatherThread(l, level, g - work.x);
  } else {
    gatherGroup(l, level, work, g - work.x);
  }
}
