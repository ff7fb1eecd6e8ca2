#version 450
// LGH scatter: every input light adds its trilinear share to the 8 grid vertices of its cell at
// level u_level. Used for S1 by both methods (few lights per vertex at the finest level, so the
// atomics rarely collide) and, for the scatter-every-level method, for every level (where the
// coarse levels' few vertices make the atomics collide: the paper's Table 1 contrast). The
// binned S1 (lgh_bin_*.comp) replaces it for S1 on large inputs (LghS1Scatter).
// Per vertex: sum w*rgb, sum w*I*u and sum w*I*u^2 with u = (p - vertex) / h_l in (-1, 1) and
// I = luminance(rgb): cell units keep the variance free of large-coordinate cancellation.
#define LGH_BUILD_INTERNALS
#include "include/lgh_types.glsl"

layout(local_size_x = LGH_GROUP) in;

uniform uint u_level;
uniform uint u_clearWords;  // level 1: occupancy bitmap words to clear (lgh_occupancy.comp's)

void main() {
  const uint i = lghGroupIndex() * LGH_GROUP + gl_LocalInvocationID.x;
  // The auto-level bitmaps are done with: clear them here rather than by a separate command.
  const uint threads = gl_NumWorkGroups.x * gl_NumWorkGroups.y * LGH_GROUP;
  for (uint w = i; w < u_clearWords; w += threads) bitmap[w] = 0u;
  if (i >= st.lightCount || u_level > lgh.levelCount) return;
  const PointLight light = lights[i];
  const vec3 rgb = light.intensityPad.rgb;
  const float lum = luminance(rgb);
  if (lum <= 0.0) return;
  const LghLevel level = lgh.level[u_level - 1u];
  const vec3 t = lghGridCoordinate(light.positionPad.xyz, u_level);
  for (uint corner = 0u; corner < 8u; ++corner) {
    uvec3 v;
    vec3 wRgb, moment1, moment2;
    if (!lghCornerShare(t, rgb, lum, corner, v, wRgb, moment1, moment2)) continue;
    lghAccumulate(level.denseOffset + lghEncode(v, level.dims.xyz), wRgb, moment1, moment2);
  }
}
