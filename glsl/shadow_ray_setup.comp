#version 450 core
// Shadow ray setup: one invocation per pixel writes the pixel's ray origin (its G-buffer position
// moved off the surface along the normal) and its targets: uLightSamples points (or directions)
// on each shadowed direct light, jittered over the light's radius for soft shadows (none where
// the light cannot light the surface: directLightReaches), then the LGH's k shadow samples
// (already jittered by the grid light's variance, Sec. 3.3).
// With LGH_POINT_LIGHT_RAYS (the shadowed brute-force reference): one ray to each of
// uRaysPerPixel point lights of the PointLight SSBO from uFirstLight on, at their exact positions.
// Inputs: G-buffer position and normal, lights SSBO, LGH samples. Outputs: origins, targets.
// A pixel without a surface gets origin w = 0 (no rays) and no targets: the tracer reads none of
// them. On a CPU rasteriser the pass clears the origins first, so that invocation groups of
// background pixels write nothing (include/skip_background.glsl): a store there is a scalar loop
// over the SIMD lanes.

#include "include/skip_background.glsl"
#include "include/gbuffer.glsl"
#include "include/lights.glsl"
#include "include/reservoir.glsl"
#include "include/ray_batch.glsl"
#ifdef LGH_POINT_LIGHT_RAYS
#include "include/lgh_types.glsl"
layout(std430, binding = LGH_BIND_POINT_LIGHTS) readonly buffer PointLights {
  PointLight pointLights[];
};
uniform int uFirstLight;
#endif

layout(local_size_x = LGH_GROUP_2D, local_size_y = LGH_GROUP_2D) in;
// The dispatch covers the tiles from uFirstTile on: all of them, or where the output was cleared
// before, those that can show a surface (passes/surface_tiles.hpp).
uniform uvec2 uFirstTile;
#define LGH_FIRST_TILE uFirstTile
#include "include/balanced_tiles.glsl"  // after the work-group size

layout(std430, binding = LGH_BIND_LIGHTS) readonly buffer Lights { Light lights[]; };
layout(std430, binding = LGH_BIND_SAMPLES) readonly buffer LghSamples {
  vec4 lghSamples[];  // vec4(position, weight); weight 0: no light
};
layout(std430, binding = LGH_BIND_RAY_ORIGINS) writeonly buffer RayOrigins { vec4 origins[]; };
layout(std430, binding = LGH_BIND_RAY_TARGETS) writeonly buffer RayTargets { vec4 targets[]; };

uniform ivec2 uFrameSize;
uniform int uLghSampleCount;  // k; 0 when the frame has no LGH samples
uniform float uSurfaceOffset;  // world units the origin moves along the normal
uniform uint uSeed;
uniform bool uOriginsCleared;  // every origin is (0, 0, 0, 0) already

const vec4 NO_RAY = vec4(0.0, 0.0, 0.0, -1.0);

// Two uniform numbers in [0, 1) for (pixel, light, sample).
vec2 jitter(uint pixelSeed, int light, int sampleIndex) {
  uint seed = reservoirLightSeed(pixelSeed, uint(light));
  return vec2(reservoirRandom(seed, uint(sampleIndex), 1u),
              reservoirRandom(seed, uint(sampleIndex), 2u));
}

// An orthonormal basis around unit n (Duff et al. 2017).
void basis(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// A point on the disk of radius r facing `origin`, centred on `center` (uniform by area).
vec3 diskPoint(vec3 center, float r, vec3 origin, vec2 u) {
  if (r <= 0.0) return center;
  vec3 t, b;
  basis(normalize(center - origin), t, b);
  float rho = r * sqrt(u.x);
  float phi = 2.0 * PI * u.y;
  return center + rho * (cos(phi) * t + sin(phi) * b);
}

// A direction in the cone of half-angle `angle` around unit `axis` (uniform by solid angle).
vec3 coneDirection(vec3 axis, float angle, vec2 u) {
  if (angle <= 0.0) return axis;
  vec3 t, b;
  basis(axis, t, b);
  float cosTheta = 1.0 - u.x * (1.0 - cos(angle));
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * PI * u.y;
  return cosTheta * axis + sinTheta * (cos(phi) * t + sin(phi) * b);
}

// An LGH sample jittered behind the surface's tangent plane, mirrored to the front: light from
// behind the plane never reaches the surface (its unshadowed contribution, taken at the grid
// light's centre, counts only what arrives from the front), so the surface itself must not
// count as its occluder. Without it, grid lights that merge VPLs of neighbouring surfaces put
// part of their jitter behind every receiver near them, and the frame came out a third too dark
// against the shadowed brute force (docs/GI.md).
vec3 inFrontOf(vec3 target, vec3 surface, vec3 normal) {
  float behind = dot(target - surface, normal);
  return behind < 0.0 ? target - 2.0 * behind * normal : target;
}

// Whether light `l` can light the surface directly at all as the direct lighting pass evaluates
// it (include/light_terms.glsl, include/brdf.glsl): not outside its range or cone, nor on an unlit
// surface, nor from behind the surface unless the surface transmits. Where it cannot, that pass
// never reads the rays' bits, so none is traced. The margin keeps a ray where the pass, another
// program, might round the same dot product to the other side of 0.
bool directLightReaches(Light l, SurfacePoint s) {
  if (s.model == MATERIAL_MODEL_UNLIT) return false;
  vec3 toLight;
  if (!(lightFalloff(l, s.position, toLight) > 0.0)) return false;
  bool mayTransmit = !isClassicModel(s.model) && (s.layers & MATERIAL_LAYER_TRANSMISSION) != 0u;
  return mayTransmit || dot(s.normal, toLight) > -1e-4;
}

vec4 directTarget(int light, int sampleIndex, vec3 origin, uint pixelSeed) {
  Light l = lights[light];
  int type = int(l.positionType.w + 0.5);
  vec2 u = jitter(pixelSeed, light, sampleIndex);
  float size = l.cone.z;  // radius (point, spot) or angular radius (directional)
  if (type == LIGHT_DIRECTIONAL) return vec4(coneDirection(-l.directionRange.xyz, size, u), 0.0);
  return vec4(diskPoint(l.positionType.xyz, size, origin, u), 1.0);
}

void main() {
  ivec2 pixel = balancedPixel();
  bool inFrame = all(lessThan(pixel, uFrameSize));
  uint pixelIndex = uint(pixel.y) * uint(uFrameSize.x) + uint(pixel.x);
  uint firstTarget = pixelIndex * uint(uRaysPerPixel);
  if (!anyInvocationCovers(inFrame && surfaceCovered(pixel))) {
    if (inFrame && !uOriginsCleared) origins[pixelIndex] = vec4(0.0);
    return;
  }
  if (!inFrame) return;
  SurfacePoint s;
  if (!readSurface(pixel, s)) {
    if (!uOriginsCleared) origins[pixelIndex] = vec4(0.0);
    return;
  }
  vec3 origin = s.position + s.normal * uSurfaceOffset;
  origins[pixelIndex] = vec4(origin, 1.0);
#ifdef LGH_POINT_LIGHT_RAYS
  for (int ray = 0; ray < uRaysPerPixel; ++ray) {
    targets[firstTarget + uint(ray)] = vec4(pointLights[uFirstLight + ray].positionPad.xyz, 1.0);
  }
  return;
#endif
  uint pixelSeed = reservoirPixelSeed(uSeed, pixelIndex);
  int ray = 0;
  for (int light = 0; light < uShadowedLights; ++light) {
    bool reaches = directLightReaches(lights[light], s);
    for (int sampleIndex = 0; sampleIndex < uLightSamples; ++sampleIndex) {
      targets[firstTarget + uint(ray++)] =
          reaches ? directTarget(light, sampleIndex, origin, pixelSeed) : NO_RAY;
    }
  }
  for (int k = 0; k < uLghSampleCount; ++k) {
    vec4 lghSample = lghSamples[pixelIndex * uint(uLghSampleCount) + uint(k)];
    targets[firstTarget + uint(ray++)] =
        lghSample.w > 0.0 ? vec4(inFrontOf(lghSample.xyz, s.position, s.normal), 1.0) : NO_RAY;
  }
}
