// A material at one fragment, as the G-buffer pass (gbuffer.frag) and the forward pass of blended
// surfaces (forward_blend.frag) both need it: textures sampled (with KHR_texture_transform, the
// shader's bicubic filter where asked, two-channel normal maps), the lecture's multi-texturing
// (light map, gloss and specular maps, alpha) and surface detail (normal, bump, parallax, relief
// mapping, and the normal of displaced geometry), into a SurfacePoint for include/brdf.glsl.
//
// Conventions (glTF): texture v grows down the image; a tangent frame (t, b, n) has t along +u
// and b along -v (the image's up), as MikkTSpace tangents with glTF's flipped v are. Heights are
// the height map's R, 1 at the top of the surface.
#ifndef LGH_MATERIAL_SAMPLING_GLSL
#define LGH_MATERIAL_SAMPLING_GLSL

// What the draw's material can need, known when the program is built (SurfaceProgramKey::features
// in renderer/src/passes/surface_programs.hpp): code for a feature the material lacks is compiled
// out, so that the shader holds fewer registers and, without a discard, its depth test runs
// before it. Unset: every feature (the generic shader, as the forward pass uses it).
#define LGH_MATERIAL_DISCARD 1  // the alpha test, relief silhouettes, point disks
#define LGH_MATERIAL_HEIGHT 2   // bump, parallax, relief mapping, displacement
#define LGH_MATERIAL_LAYERS 4   // KHR_materials_* layers of metallic-roughness
#define LGH_MATERIAL_CLASSIC 8  // the lecture's models (Phong and up), Gouraud and flat shading
#define LGH_MATERIAL_BICUBIC 16 // the shader's bicubic texture filter
#define LGH_MATERIAL_SURFACE_FRAME 32  // texture coordinates and tangents: a texture, or layers
#ifndef LGH_MATERIAL_FEATURES
#define LGH_MATERIAL_FEATURES 63
#endif
#define LGH_MATERIAL_HAS(feature) ((LGH_MATERIAL_FEATURES & (feature)) != 0)

#define LGH_LIGHTS_BUFFER
#include "include/common.glsl"
#include "include/gbuffer_encoding.glsl"
#include "include/lights.glsl"
#include "include/material_slots.glsl"

layout(binding = SLOT_BASE_COLOR) uniform sampler2D uBaseColorTexture;
layout(binding = SLOT_METALLIC_ROUGHNESS) uniform sampler2D uMetallicRoughnessTexture;
layout(binding = SLOT_NORMAL) uniform sampler2D uNormalTexture;
layout(binding = SLOT_OCCLUSION) uniform sampler2D uOcclusionTexture;
layout(binding = SLOT_EMISSIVE) uniform sampler2D uEmissiveTexture;
layout(binding = SLOT_CLEARCOAT) uniform sampler2D uClearcoatTexture;
layout(binding = SLOT_CLEARCOAT_ROUGHNESS) uniform sampler2D uClearcoatRoughnessTexture;
layout(binding = SLOT_CLEARCOAT_NORMAL) uniform sampler2D uClearcoatNormalTexture;
layout(binding = SLOT_SHEEN_COLOR) uniform sampler2D uSheenColorTexture;
layout(binding = SLOT_SHEEN_ROUGHNESS) uniform sampler2D uSheenRoughnessTexture;
layout(binding = SLOT_SPECULAR) uniform sampler2D uSpecularTexture;
layout(binding = SLOT_SPECULAR_COLOR) uniform sampler2D uSpecularColorTexture;
layout(binding = SLOT_TRANSMISSION) uniform sampler2D uTransmissionTexture;
layout(binding = SLOT_LIGHT_MAP) uniform sampler2D uLightMapTexture;
layout(binding = SLOT_HEIGHT) uniform sampler2D uHeightTexture;

// glTF metallic-roughness and its layers.
uniform vec4 uBaseColorFactor;
uniform float uMetallicFactor;
uniform float uRoughnessFactor;
uniform vec3 uEmissiveFactor;
uniform float uNormalScale;
uniform float uOcclusionStrength;
uniform float uAlphaCutoff;  // < 0: no alpha test
uniform vec3 uCameraPosition;
uniform uint uModel;         // MATERIAL_MODEL_*
uniform uint uLayers;        // MATERIAL_LAYER_*
uniform vec3 uClearcoat;     // factor, roughness, normal scale
uniform vec4 uSheen;         // colour rgb, roughness
uniform vec4 uSpecular;      // colour rgb, factor
uniform float uDielectricF0; // ((ior - 1) / (ior + 1))^2
uniform float uTransmission;
uniform vec3 uTransmissionTint;
// The classic models.
uniform vec3 uAmbientColor;
uniform bool uAmbientIsDiffuse;  // ambient_material unset: the (textured) diffuse colour
uniform vec3 uSpecularColor;     // Cook-Torrance: F0
uniform float uExponent;         // shininess, sigma or m
uniform uint uShading;           // 0 per pixel, 1 Gouraud, 2 flat
// Texturing.
uniform bool uBicubic;
uniform uint uTwoChannelMask;  // bit per slot: a two-channel normal map (BC5), z rebuilt
uniform float uLightMapStrength;
// Surface detail.
uniform uint uSurface;  // SURFACE_*
uniform float uHeightScale;
uniform float uParallaxBias;
uniform int uReliefLinearSteps;
uniform int uReliefBinarySteps;
uniform bool uReliefSelfShadow;
uniform bool uReliefSilhouettes;
uniform bool uHasTangents;  // the mesh carries a tangent frame; else one from derivatives
uniform int uLightCount;    // relief self-shadowing: the analytic lights

#define SURFACE_NONE 0u
#define SURFACE_NORMAL 1u
#define SURFACE_BUMP 2u
#define SURFACE_PARALLAX 3u
#define SURFACE_RELIEF 4u
#define SURFACE_DISPLACEMENT 5u

// What the fragment stage gets per vertex, interpolated.
struct FragmentInputs {
  vec3 position;
  vec3 basePosition;
  vec3 normal;
  vec4 tangent;
  vec2 uv0;
  vec2 uv1;
  vec4 color;
  vec3 diffuseLight;
  vec3 specularLight;
};

// Screen-space derivatives, taken once at the top of main() where control flow is uniform.
struct Derivatives {
  vec3 dPdx;
  vec3 dPdy;
  vec2 dUv0dx;
  vec2 dUv0dy;
  vec2 dUv1dx;
  vec2 dUv1dy;
};

Derivatives screenDerivatives(FragmentInputs f) {
  return Derivatives(dFdx(f.basePosition), dFdy(f.basePosition), dFdx(f.uv0), dFdy(f.uv0),
                     dFdx(f.uv1), dFdy(f.uv1));
}

// ---- sampling ----------------------------------------------------------------------------------

// Catmull-Rom bicubic filtering from nine bilinear taps (the weights of the four taps per axis
// folded into three where they share a sign), on mip level 0. It applies where the texture is
// magnified; towards minification it hands over to the sampler's mip filtering over one level,
// where a bicubic kernel on level 0 would alias.
vec4 sampleBicubic(sampler2D map, vec2 uv) {
  float lod = textureQueryLod(map, uv).y;
  if (lod >= 1.0) return texture(map, uv);
  vec2 size = vec2(textureSize(map, 0));
  vec2 position = uv * size;
  vec2 center1 = floor(position - 0.5) + 0.5;
  vec2 f = position - center1;
  vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
  vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
  vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
  vec2 w3 = f * f * (-0.5 + 0.5 * f);
  vec2 w12 = w1 + w2;
  vec2 t0 = (center1 - 1.0) / size;
  vec2 t12 = (center1 + w2 / w12) / size;
  vec2 t3 = (center1 + 2.0) / size;
  vec4 result = vec4(0.0);
  result += textureLod(map, vec2(t0.x, t0.y), 0.0) * w0.x * w0.y;
  result += textureLod(map, vec2(t12.x, t0.y), 0.0) * w12.x * w0.y;
  result += textureLod(map, vec2(t3.x, t0.y), 0.0) * w3.x * w0.y;
  result += textureLod(map, vec2(t0.x, t12.y), 0.0) * w0.x * w12.y;
  result += textureLod(map, vec2(t12.x, t12.y), 0.0) * w12.x * w12.y;
  result += textureLod(map, vec2(t3.x, t12.y), 0.0) * w3.x * w12.y;
  result += textureLod(map, vec2(t0.x, t3.y), 0.0) * w0.x * w3.y;
  result += textureLod(map, vec2(t12.x, t3.y), 0.0) * w12.x * w3.y;
  result += textureLod(map, vec2(t3.x, t3.y), 0.0) * w3.x * w3.y;
  return lod > 0.0 ? mix(result, texture(map, uv), lod) : result;
}

vec4 sampleMap(sampler2D map, vec2 uv) {
  return LGH_MATERIAL_HAS(LGH_MATERIAL_BICUBIC) && uBicubic ? sampleBicubic(map, uv)
                                                           : texture(map, uv);
}

// The material's current texture coordinates: parallax and relief mapping move them.
struct Uvs {
  vec2 uv0;
  vec2 uv1;
};

vec2 uvFor(int slot, Uvs uvs) { return slotUv(slot, uvs.uv0, uvs.uv1); }

vec4 sampleSlot(int slot, sampler2D map, Uvs uvs) { return sampleMap(map, uvFor(slot, uvs)); }

float sampleChannel(int slot, sampler2D map, Uvs uvs, int channel) {
  return hasTexture(slot) ? sampleSlot(slot, map, uvs)[channel] : 1.0;
}

vec3 sampleColor(int slot, sampler2D map, Uvs uvs) {
  return hasTexture(slot) ? sampleSlot(slot, map, uvs).rgb : vec3(1.0);
}

// A tangent-space normal from a normal map texel (three channels, or two with z rebuilt).
vec3 decodeNormalTexel(int slot, vec4 texel) {
  if ((uTwoChannelMask & (1u << uint(slot))) != 0u) {
    vec2 xy = texel.rg * 2.0 - 1.0;
    return vec3(xy, sqrt(max(1.0 - dot(xy, xy), 0.0)));
  }
  return texel.xyz * 2.0 - 1.0;
}

// ---- tangent frames ----------------------------------------------------------------------------

struct TangentFrame {
  vec3 t;  // along +u
  vec3 b;  // along -v (the image's up)
  vec3 n;
};

// The mesh's frame where it has one. Otherwise the lecture's "UVW to object space" solved per
// pixel: Q (du, dv) = dP for the two screen directions gives dP/du and dP/dv (Schueler 2013).
TangentFrame tangentFrame(FragmentInputs f, Derivatives d, vec3 n, int uvSet) {
  TangentFrame frame;
  frame.n = n;
  vec3 t = f.tangent.xyz - n * dot(n, f.tangent.xyz);
  if (uHasTangents && dot(t, t) > 1e-12) {
    frame.t = normalize(t);
    frame.b = cross(n, frame.t) * (f.tangent.w < 0.0 ? -1.0 : 1.0);
    return frame;
  }
  vec2 du = uvSet == 1 ? d.dUv1dx : d.dUv0dx;
  vec2 dv = uvSet == 1 ? d.dUv1dy : d.dUv0dy;
  float det = du.x * dv.y - dv.x * du.y;
  vec3 dPdu = (d.dPdx * dv.y - d.dPdy * du.y);
  vec3 dPdv = (d.dPdy * du.x - d.dPdx * dv.x);
  if (abs(det) < 1e-20) {
    frame.t = abs(n.x) < 0.9 ? normalize(cross(n, vec3(1.0, 0.0, 0.0)))
                             : normalize(cross(n, vec3(0.0, 1.0, 0.0)));
    frame.b = cross(n, frame.t);
    return frame;
  }
  dPdu *= sign(det);
  dPdv *= sign(det);
  dPdu -= n * dot(n, dPdu);
  dPdv -= n * dot(n, dPdv);
  frame.t = dot(dPdu, dPdu) > 1e-24 ? normalize(dPdu) : cross(vec3(0.0, 1.0, 0.0), n);
  frame.b = dot(dPdv, dPdv) > 1e-24 ? -normalize(dPdv) : cross(n, frame.t);
  return frame;
}

vec3 toTangentSpace(TangentFrame frame, vec3 v) {
  return vec3(dot(v, frame.t), dot(v, frame.b), dot(v, frame.n));
}

vec3 fromTangentSpace(TangentFrame frame, vec3 v) {
  return normalize(frame.t * v.x + frame.b * v.y + frame.n * v.z);
}

// A tangent-space direction's (x, y) as a texture-coordinate offset: b points along -v.
vec2 tangentToUv(vec2 xy) { return vec2(xy.x, -xy.y); }

// ---- the height map ----------------------------------------------------------------------------

int heightUvSet() { return slotUsesUv1(SLOT_HEIGHT) ? 1 : 0; }

// The height map, sampled with the fragment's own derivatives (inside loops the implicit ones are
// undefined).
float heightAt(vec2 uv, vec2 gradX, vec2 gradY) {
  return textureGrad(uHeightTexture, uv, gradX, gradY).r;
}

// The height map's slope dh/du, dh/dv at uv by central differences over one texel.
vec2 heightSlope(vec2 uv, vec2 gradX, vec2 gradY) {
  vec2 texel = 1.0 / vec2(textureSize(uHeightTexture, 0));
  float left = heightAt(uv - vec2(texel.x, 0.0), gradX, gradY);
  float right = heightAt(uv + vec2(texel.x, 0.0), gradX, gradY);
  float up = heightAt(uv - vec2(0.0, texel.y), gradX, gradY);
  float down = heightAt(uv + vec2(0.0, texel.y), gradX, gradY);
  return vec2(right - left, down - up) / (2.0 * texel);
}

// The height-map slope as a transformed-texture-coordinate gradient, mapped back through the
// slot's KHR_texture_transform to the mesh's UV set (the chain rule through the 2x2 part).
vec2 slopeInMeshUv(vec2 slope) { return transpose(mat2(uUvTransform[SLOT_HEIGHT][0], uUvTransform[SLOT_HEIGHT][1])) * slope; }

// Bump mapping (and the normal of displaced geometry): the surface moved along n by
// uHeightScale x h, in world units, whose normal is Mikkelsen's surface gradient (2010) from the
// screen derivatives of the position and of the height, the height's by the chain rule from its
// central differences in texture space.
vec3 bumpNormal(vec3 n, Derivatives d, vec2 uv) {
  int set = heightUvSet();
  vec2 uvDx = set == 1 ? d.dUv1dx : d.dUv0dx;
  vec2 uvDy = set == 1 ? d.dUv1dy : d.dUv0dy;
  mat2 transform = mat2(uUvTransform[SLOT_HEIGHT][0], uUvTransform[SLOT_HEIGHT][1]);
  vec2 gradX = transform * uvDx;
  vec2 gradY = transform * uvDy;
  vec2 slope = slopeInMeshUv(heightSlope(uv, gradX, gradY)) * uHeightScale;
  float dHdx = dot(slope, uvDx);
  float dHdy = dot(slope, uvDy);
  vec3 r1 = cross(d.dPdy, n);
  vec3 r2 = cross(n, d.dPdx);
  float det = dot(d.dPdx, r1);
  if (abs(det) < 1e-30) return n;
  vec3 gradient = sign(det) * (dHdx * r1 + dHdy * r2);
  vec3 bumped = normalize(abs(det) * n - gradient);
  return any(isnan(bumped)) ? n : bumped;
}

// The lecture's parallax mapping: h_n = s h - b, T_n = T_0 + h_n V.xy with V the unit view
// vector in tangent space. Returns the offset of the height map's coordinates.
vec2 parallaxOffset(vec3 viewTangent, vec2 uv, vec2 gradX, vec2 gradY) {
  float h = heightAt(uv, gradX, gradY);
  float hn = uHeightScale * h - uParallaxBias;
  return hn * tangentToUv(viewTangent.xy);
}

// Relief mapping (Policarpo, Oliveira & Comba 2005): the view ray marched through the height
// field, depth 0 at the top and 1 at the bottom (uHeightScale deep in texture units), first in
// uReliefLinearSteps equal steps to the first point below the surface, then refined by
// uReliefBinarySteps halvings. Returns the coordinates hit (xy) and the depth there (z).
vec3 reliefIntersection(vec3 viewTangent, vec2 uv, vec2 gradX, vec2 gradY) {
  // Along the ray, a unit of depth moves the coordinates by this much.
  vec2 perDepth = -tangentToUv(viewTangent.xy / max(viewTangent.z, 0.05)) * uHeightScale;
  float step = 1.0 / float(max(uReliefLinearSteps, 1));
  float depth = 0.0;
  for (int i = 0; i < uReliefLinearSteps; ++i) {
    if (depth >= 1.0 - heightAt(uv + perDepth * depth, gradX, gradY)) break;
    depth += step;
  }
  float below = min(depth, 1.0);
  float above = max(depth - step, 0.0);
  for (int i = 0; i < uReliefBinarySteps; ++i) {
    float middle = 0.5 * (above + below);
    if (middle >= 1.0 - heightAt(uv + perDepth * middle, gradX, gradY)) {
      below = middle;
    } else {
      above = middle;
    }
  }
  return vec3(uv + perDepth * below, below);
}

// Whether the height field hides a light (tangent-space direction toLight) from the point found
// at `hit`: the ray towards the light, marched up to the top. Heights within RELIEF_SHADOW_BIAS
// (of the relief's depth) above the ray do not count: fine noise would otherwise shadow itself
// in speckles (acne).
#define RELIEF_SHADOW_BIAS 0.08
bool reliefShadowed(vec3 hit, vec3 lightTangent, vec2 gradX, vec2 gradY) {
  if (lightTangent.z <= 0.0 || hit.z <= 0.0) return false;
  vec2 perDepth = tangentToUv(lightTangent.xy / max(lightTangent.z, 0.05)) * uHeightScale;
  int steps = max(uReliefLinearSteps / 2, 4);
  float step = hit.z / float(steps);
  for (int i = 1; i < steps; ++i) {
    float depth = hit.z - step * float(i);
    vec2 uv = hit.xy + perDepth * (hit.z - depth);
    if (1.0 - heightAt(uv, gradX, gradY) < depth - RELIEF_SHADOW_BIAS) return true;
  }
  return false;
}

// ---- the material ------------------------------------------------------------------------------

struct MaterialSample {
  SurfacePoint surface;
  vec3 emissive;
  float alpha;
  bool discarded;  // the alpha test or relief mapping's silhouette took the fragment
  uint flags;      // the material target's alpha byte: layer bits, or classic flags
};

// The layer parameters of this fragment into s (defaults where a layer is off).
void sampleLayers(vec3 geometricNormal, TangentFrame frame, Uvs uvs, inout SurfacePoint s) {
  if ((uLayers & MATERIAL_LAYER_CLEARCOAT) != 0u) {
    s.clearcoat = uClearcoat.x * sampleChannel(SLOT_CLEARCOAT, uClearcoatTexture, uvs, 0);
    s.clearcoatRoughness =
        uClearcoat.y * sampleChannel(SLOT_CLEARCOAT_ROUGHNESS, uClearcoatRoughnessTexture, uvs, 1);
    s.clearcoatNormal = geometricNormal;
    if (hasTexture(SLOT_CLEARCOAT_NORMAL)) {
      vec3 n = decodeNormalTexel(SLOT_CLEARCOAT_NORMAL,
                                 sampleSlot(SLOT_CLEARCOAT_NORMAL, uClearcoatNormalTexture, uvs));
      n.xy *= uClearcoat.z;
      vec3 mapped = fromTangentSpace(frame, n);
      if (!any(isnan(mapped))) s.clearcoatNormal = mapped;
    }
  }
  if ((uLayers & MATERIAL_LAYER_SHEEN) != 0u) {
    s.sheenColor = uSheen.rgb * sampleColor(SLOT_SHEEN_COLOR, uSheenColorTexture, uvs);
    s.sheenRoughness = uSheen.a * sampleChannel(SLOT_SHEEN_ROUGHNESS, uSheenRoughnessTexture, uvs, 3);
  }
  if ((uLayers & MATERIAL_LAYER_SPECULAR) != 0u) {
    s.specularWeight = uSpecular.a * sampleChannel(SLOT_SPECULAR, uSpecularTexture, uvs, 3);
    s.dielectricF0 = min(uDielectricF0 * uSpecular.rgb *
                             sampleColor(SLOT_SPECULAR_COLOR, uSpecularColorTexture, uvs),
                         vec3(1.0));
  }
  if ((uLayers & MATERIAL_LAYER_TRANSMISSION) != 0u) {
    s.transmission = uTransmission * sampleChannel(SLOT_TRANSMISSION, uTransmissionTexture, uvs, 0);
    s.transmissionTint = uTransmissionTint;
  }
}

// The relief self-shadowing mask of the first 23 analytic lights at the hit point.
uint reliefSelfShadowMask(vec3 hit, TangentFrame frame, vec3 position, vec2 gradX, vec2 gradY) {
  uint mask = 0u;
  int count = min(uLightCount, 23);
  for (int i = 0; i < count; ++i) {
    vec3 toLight;
    if (lightFalloff(lights[i], position, toLight) <= 0.0) continue;
    if (reliefShadowed(hit, toTangentSpace(frame, toLight), gradX, gradY)) mask |= 1u << uint(i);
  }
  return mask;
}

// The shading normal from the normal map (tangent space, scaled by uNormalScale).
vec3 normalMapNormal(TangentFrame frame, Uvs uvs) {
  vec3 n = decodeNormalTexel(SLOT_NORMAL, sampleSlot(SLOT_NORMAL, uNormalTexture, uvs));
  n.xy *= uNormalScale;
  vec3 mapped = fromTangentSpace(frame, n);
  return any(isnan(mapped)) ? frame.n : mapped;
}

// Parallax and relief surfaces without a normal map take the height map's slope at the
// displaced coordinates, in the same tangent-space units as the height (texture units).
vec3 heightSlopeNormal(TangentFrame frame, vec2 uv, vec2 gradX, vec2 gradY) {
  vec2 slope = heightSlope(uv, gradX, gradY) * uHeightScale;
  return fromTangentSpace(frame, vec3(-slope.x, slope.y, 1.0));
}

MaterialSample sampleMaterial(FragmentInputs f, Derivatives d) {
  MaterialSample result;
  result.discarded = false;
  vec3 geometric = normalize(f.normal);
  if (any(isnan(geometric))) geometric = vec3(0.0, 1.0, 0.0);
  // Shade the side the camera sees (double-sided materials, and mirrored instances).
  vec3 toViewer = normalize(uCameraPosition - f.position);
  if (dot(geometric, toViewer) < 0.0) geometric = -geometric;

  Uvs uvs = Uvs(f.uv0, f.uv1);
  bool height = LGH_MATERIAL_HAS(LGH_MATERIAL_HEIGHT) && hasTexture(SLOT_HEIGHT);
  int heightSet = heightUvSet();
  // The tangent frame only where something reads it: plain surfaces skip its per-pixel solve.
  bool layered = LGH_MATERIAL_HAS(LGH_MATERIAL_LAYERS) && uModel == MATERIAL_MODEL_METALLIC_ROUGHNESS &&
                 uLayers != 0u;
  TangentFrame frame = TangentFrame(vec3(0.0), vec3(0.0), geometric);
  if (height || hasTexture(SLOT_NORMAL) || layered) {
    frame = tangentFrame(f, d, geometric,
                         hasTexture(SLOT_NORMAL) && slotUsesUv1(SLOT_NORMAL) ? 1 : heightSet);
  }
  mat2 heightTransform = mat2(uUvTransform[SLOT_HEIGHT][0], uUvTransform[SLOT_HEIGHT][1]);
  vec2 gradX = heightTransform * (heightSet == 1 ? d.dUv1dx : d.dUv0dx);
  vec2 gradY = heightTransform * (heightSet == 1 ? d.dUv1dy : d.dUv0dy);
  vec2 heightUv = slotUv(SLOT_HEIGHT, f.uv0, f.uv1);
  vec3 reliefHit = vec3(heightUv, 0.0);
  bool moved = false;
  if (height && (uSurface == SURFACE_PARALLAX || uSurface == SURFACE_RELIEF)) {
    vec3 viewTangent = toTangentSpace(frame, toViewer);
    vec2 offset;
    if (uSurface == SURFACE_PARALLAX) {
      offset = parallaxOffset(viewTangent, heightUv, gradX, gradY);
    } else {
      reliefHit = reliefIntersection(viewTangent, heightUv, gradX, gradY);
      offset = reliefHit.xy - heightUv;
      if (LGH_MATERIAL_HAS(LGH_MATERIAL_DISCARD) && uReliefSilhouettes && (any(lessThan(reliefHit.xy, vec2(0.0))) ||
                                 any(greaterThan(reliefHit.xy, vec2(1.0))))) {
        result.discarded = true;
      }
    }
    // The offset is in the height map's transformed coordinates; move the mesh's UV set by it.
    vec2 meshOffset = inverse(heightTransform) * offset;
    if (heightSet == 1) {
      uvs.uv1 += meshOffset;
    } else {
      uvs.uv0 += meshOffset;
    }
    heightUv += offset;
    moved = true;
  }

  vec4 baseColor = uBaseColorFactor * f.color;
  if (hasTexture(SLOT_BASE_COLOR)) baseColor *= sampleSlot(SLOT_BASE_COLOR, uBaseColorTexture, uvs);
  result.alpha = baseColor.a;
  if (LGH_MATERIAL_HAS(LGH_MATERIAL_DISCARD) && uAlphaCutoff >= 0.0 &&
      baseColor.a < uAlphaCutoff) {
    result.discarded = true;
  }

  vec3 n = geometric;
  bool normalMap = hasTexture(SLOT_NORMAL) && uSurface != SURFACE_NONE && uSurface != SURFACE_BUMP &&
                   uSurface != SURFACE_DISPLACEMENT;
  if (normalMap) {
    n = normalMapNormal(frame, uvs);
  } else if (height && (uSurface == SURFACE_BUMP || uSurface == SURFACE_DISPLACEMENT)) {
    n = bumpNormal(geometric, d, heightUv);
  } else if (height && moved) {
    n = heightSlopeNormal(frame, heightUv, gradX, gradY);
  }

  float metallic = uMetallicFactor;
  float roughness = uRoughnessFactor;
  if (hasTexture(SLOT_METALLIC_ROUGHNESS)) {
    vec4 mr = sampleSlot(SLOT_METALLIC_ROUGHNESS, uMetallicRoughnessTexture, uvs);
    roughness *= mr.g;
    metallic *= mr.b;
  }
  float occlusion = 1.0;
  if (hasTexture(SLOT_OCCLUSION)) {
    occlusion = 1.0 + uOcclusionStrength *
                          (sampleSlot(SLOT_OCCLUSION, uOcclusionTexture, uvs).r - 1.0);
  }
  vec3 emissive = uEmissiveFactor;
  if (hasTexture(SLOT_EMISSIVE)) emissive *= sampleSlot(SLOT_EMISSIVE, uEmissiveTexture, uvs).rgb;
  // Unlit: the base colour is what the surface shows, emitted beside its emission (glTF's rule
  // for lines and points without normals; KHR_materials_unlit shows the base colour alone).
  if (uModel == MATERIAL_MODEL_UNLIT) emissive += baseColor.rgb;

  SurfacePoint s = defaultSurface(f.position, n, saturate(baseColor.rgb), saturate(metallic),
                                  saturate(roughness), saturate(occlusion));
  s.model = uModel;
  // The light map: precomputed illumination of the diffuse colour (the lecture's diffuse x light).
  if (hasTexture(SLOT_LIGHT_MAP)) {
    emissive += s.baseColor * sampleSlot(SLOT_LIGHT_MAP, uLightMapTexture, uvs).rgb *
                uLightMapStrength;
  }
  result.flags = 0u;
  if (LGH_MATERIAL_HAS(LGH_MATERIAL_CLASSIC) && isClassicModel(uModel)) {
    s.ambientColor = uAmbientIsDiffuse ? s.baseColor : uAmbientColor;
    vec3 specularMap = sampleColor(SLOT_SPECULAR_COLOR, uSpecularColorTexture, uvs);
    s.specularColor = uSpecularColor * specularMap;
    s.exponent = uExponent;
    bool glossy = uModel == MATERIAL_MODEL_PHONG || uModel == MATERIAL_MODEL_BLINN_PHONG;
    if (glossy && hasTexture(SLOT_SPECULAR)) {
      s.exponent *= sampleSlot(SLOT_SPECULAR, uSpecularTexture, uvs).r;
    }
    if (uShading != 0u) {
      // Gouraud / flat: the interpolated sums times the fragment's colours (the lecture's
      // texture modulating per-vertex lighting, with a separate specular colour).
      vec3 specularScale = uModel == MATERIAL_MODEL_COOK_TORRANCE ? specularMap : s.specularColor;
      s.hasVertexLit = true;
      s.vertexLit = f.diffuseLight * s.baseColor + f.specularLight * specularScale;
      result.flags = MATERIAL_CLASSIC_VERTEX_LIT;
    }
  } else if (uModel == MATERIAL_MODEL_METALLIC_ROUGHNESS) {
    s.layers = uLayers;
    result.flags = uLayers;
    if (LGH_MATERIAL_HAS(LGH_MATERIAL_LAYERS) && uLayers != 0u) {
      sampleLayers(geometric, frame, uvs, s);
    }
  }
  if (height && uSurface == SURFACE_RELIEF && uReliefSelfShadow) {
    s.selfShadowMask = reliefSelfShadowMask(reliefHit, frame, f.position, gradX, gradY);
  }
  result.surface = s;
  result.emissive = emissive;
  return result;
}

#endif
