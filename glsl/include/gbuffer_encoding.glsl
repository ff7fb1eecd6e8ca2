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

// Shared-exponent RGB (9 bits of mantissa each, 5 of exponent): HDR radiance in one word.
uint packRgb9e5(vec3 rgb) {
  const float kMax = 65408.0;  // (511 / 512) * 2^16
  vec3 c = clamp(rgb, vec3(0.0), vec3(kMax));
  float largest = max(max(c.r, c.g), max(c.b, 1e-20));
  int exponent = max(-16, int(floor(log2(largest)))) + 16;
  float step = exp2(float(exponent - 24));
  if (floor(largest / step + 0.5) >= 512.0) {
    step *= 2.0;
    exponent += 1;
  }
  uvec3 m = uvec3(min(floor(c / step + 0.5), vec3(511.0)));
  return m.r | (m.g << 9) | (m.b << 18) | (uint(exponent) << 27);
}

vec3 unpackRgb9e5(uint v) {
  float step = exp2(float(int(v >> 27) - 24));
  return vec3(float(v & 511u), float((v >> 9) & 511u), float((v >> 18) & 511u)) * step;
}

// The classic models' words: ambient colour, specular colour (Cook-Torrance: F0; square roots
// keep small values precise in 8 bits), the exponent as a float, and the per-vertex/primitive
// lighting of Gouraud and flat shading.
uvec4 encodeClassic(SurfacePoint s) {
  return uvec4(packUnorm4x8(vec4(saturate(s.ambientColor), 0.0)),
               packUnorm4x8(vec4(sqrt(saturate(s.specularColor)), 0.0)),
               floatBitsToUint(s.exponent), s.hasVertexLit ? packRgb9e5(s.vertexLit) : 0u);
}

void decodeClassic(uvec4 words, uint flags, inout SurfacePoint s) {
  s.ambientColor = unpackUnorm4x8(words.x).rgb;
  vec3 specular = unpackUnorm4x8(words.y).rgb;
  s.specularColor = specular * specular;
  s.exponent = uintBitsToFloat(words.z);
  s.hasVertexLit = (flags & MATERIAL_CLASSIC_VERTEX_LIT) != 0u;
  s.vertexLit = s.hasVertexLit ? unpackRgb9e5(words.w) : vec3(0.0);
}

#endif
