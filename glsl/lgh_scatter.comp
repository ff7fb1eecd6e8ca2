#version 450
// LGH scatter: every input light adds its trilinear share to the 8 grid vertices of its cell at
// level u_level. Used for S1 by both methods (few lights per vertex at the finest level, so the
// atomics rarely collide) and, for the scatter-every-level method, for every level (where the
// coarse levels' few vertices make the atomics collide: the paper's Table 1 contrast).
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
  const float cells = float(1u << (lgh.levelCount - u_level));
  precise vec3 t = min((light.positionPad.xyz - lgh.originH1.xyz) * level.cell.y, vec3(cells));
  const vec3 i0 = floor(t);
  const vec3 f = t - i0;
  for (uint corner = 0u; corner < 8u; ++corner) {
    const bvec3 high = bvec3((corner & 1u) != 0u, (corner & 2u) != 0u, (corner & 4u) != 0u);
    const vec3 axisWeight = mix(1.0 - f, f, high);
    const float w = axisWeight.x * axisWeight.y * axisWeight.z;
    if (w <= 0.0) continue;
    const vec3 u = mix(f, f - 1.0, high);
    const uint vertex = level.denseOffset + lghEncode(uvec3(i0) + uvec3(high), level.dims.xyz);
    const float wi = w * lum;
    lghAccumulate(vertex, w * rgb, wi * u, wi * u * u);
  }
}
