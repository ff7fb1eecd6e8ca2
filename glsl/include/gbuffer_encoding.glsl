// How the G-buffer's layers target packs a surface's layer parameters (layout in gbuffer.glsl):
// shared by the G-buffer pass, which writes it, and every reader. No samplers here.
#ifndef LGH_GBUFFER_ENCODING_GLSL
#define LGH_GBUFFER_ENCODING_GLSL

#include "include/brdf.glsl"

// Octahedral unit-vector encoding (Cigolle et al. 2014), in [-1, 1]^2.
vec2 octahedralEncode(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  vec2 e = n.xy;
  if (n.z < 0.0) e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return e;
}

vec3 octahedralDecode(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}

uvec4 encodeLayers(SurfacePoint s) {
  return uvec4(packUnorm4x8(vec4(s.clearcoat, s.clearcoatRoughness, s.sheenRoughness,
                                 s.transmission)),
               packUnorm4x8(vec4(s.sheenColor, s.specularWeight)),
               packUnorm4x8(vec4(sqrt(saturate(s.dielectricF0)), luminance(s.transmissionTint))),
               packSnorm2x16(octahedralEncode(s.clearcoatNormal)));
}

void decodeLayers(uvec4 layers, inout SurfacePoint s) {
  vec4 x = unpackUnorm4x8(layers.x);
  vec4 y = unpackUnorm4x8(layers.y);
  vec4 z = unpackUnorm4x8(layers.z);
  s.clearcoat = x.r;
  s.clearcoatRoughness = x.g;
  s.sheenRoughness = x.b;
  s.transmission = x.a;
  s.sheenColor = y.rgb;
  s.specularWeight = y.a;
  s.dielectricF0 = z.rgb * z.rgb;
  s.transmissionTint = vec3(z.a);
  s.clearcoatNormal = octahedralDecode(unpackSnorm2x16(layers.w));
}

#endif
