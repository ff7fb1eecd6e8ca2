// Lighting from the Lighting Grid Hierarchy, shared by every path that evaluates it (raster light
// volumes, the top-level full-screen pass, the compute path) and by the brute-force reference,
// so that they differ only in which lights they visit, never in what one light contributes.
// docs/LIGHTING.md describes the paths.
//
// One light's unshadowed contribution at a surface point is
//     blend(d) * I * BRDF(l, v) * max(N.l, 0) / max(d^2, d_min^2),   d_min = LGH_MIN_DISTANCE * h_1
// with the same BRDF code as the direct lighting (include/brdf.glsl) and inverse-square falloff,
// the point lights' default (kq = 1). The clamp d_min bounds the VPL singularity: a surface point
// next to a VPL would otherwise receive unbounded light. It is one S1 cell, the scale below which
// the hierarchy cannot resolve light positions (an S1 grid light stands for the lights of the
// cells around its vertex); with half a cell, S1 lights where two surfaces meet showed as a row
// of bright dots. Levels above the start are only used beyond r_(l-1) = alpha h_(l-1) >= h_1 for
// alpha >= 1, so there one clamp for all levels acts like a per-level one. The brute-force reference uses the same clamp,
// so that the error metrics measure the hierarchy and not the clamp.
#ifndef LGH_SHADING_GLSL
#define LGH_SHADING_GLSL

#include "include/brdf.glsl"
#include "include/lgh_blend.glsl"
#include "include/lgh_types.glsl"
#include "include/reservoir.glsl"
#include "include/slots.glsl"

#define LGH_MIN_DISTANCE 1.0


layout(std430, binding = LGH_BIND_GRID_LIGHTS) readonly buffer LghGridLights {
  GridLight gridLights[];
};
layout(std430, binding = LGH_BIND_LEVELS) readonly buffer LghLevels { LghLevelTable lgh; };

uniform float uAlpha;           // r_l = alpha * h_l
uniform int uStartLevel;        // lowest level lighting uses (the paper: 1)
uniform int uSampleStartLevel;  // lowest level shadow sampling uses (the paper: 2, S1 skipped)
uniform int uSampleCount;       // k shadow samples per pixel
uniform float uShadowJitter;    // scale of the samples' positional jitter (1: the paper's)
uniform uint uSeed;             // frame seed of the reservoir decisions
uniform vec3 uCameraPosition;
uniform ivec2 uFrameSize;       // full-resolution frame
uniform int uInterleave;        // n: 1 (none), 2 or 4; n x n tiles
uniform ivec2 uTileSize;        // pixels of one tile: ceil(frame / n)

struct LghFrame {
  float alpha;
  float h1;
  float minDistance2;
  int startLevel;
  int topLevel;
};

LghFrame lghFrame() {
  LghFrame frame;
  frame.alpha = uAlpha;
  frame.h1 = lgh.originH1.w;
  frame.minDistance2 = (LGH_MIN_DISTANCE * frame.h1) * (LGH_MIN_DISTANCE * frame.h1);
  frame.startLevel = uStartLevel;
  frame.topLevel = int(lgh.levelCount);
  return frame;
}

// Unshadowed radiance towards the viewer from a point light `offset` away from the surface.
vec3 lghPointRadiance(SurfacePoint s, vec3 toViewer, vec3 offset, vec3 intensity,
                      float minDistance2) {
  float d2 = dot(offset, offset);
  vec3 toLight = offset * inversesqrt(max(d2, 1e-30));
  return intensity * (evaluateBrdfCosine(s, toViewer, toLight) / max(d2, minDistance2));
}

// A grid light's blended contribution; `blend` = 0 where the light has no influence. `level` is
// the light's level (lghLevelBlend), which the caller has checked is in use.
vec3 lghGridLightRadianceAt(SurfacePoint s, vec3 toViewer, vec3 center, vec3 intensity,
                            LghLevelBlend level, float minDistance2, out float blend) {
  vec3 offset = center - s.position;
  blend = lghBlendAt(level, length(offset));
  if (blend <= 0.0) return vec3(0.0);
  return blend * lghPointRadiance(s, toViewer, offset, intensity, minDistance2);
}

vec3 lghGridLightRadiance(SurfacePoint s, vec3 toViewer, GridLight light, LghFrame frame,
                          out float blend) {
  int level = int(light.level);
  blend = 0.0;
  if (level < frame.startLevel || level > frame.topLevel) return vec3(0.0);
  return lghGridLightRadianceAt(
      s, toViewer, light.center, light.intensity,
      lghLevelBlend(level, frame.startLevel, frame.topLevel, frame.alpha, frame.h1),
      frame.minDistance2, blend);
}

// ---- lights of a frame ----------------------------------------------------------------------
// Lighting visits the merged buffer from the start level's first light: the levels below the top
// as light volumes (or tile lists), then the top level full-screen. With interleaving, light j
// (counted from that first light) belongs to tile j mod n^2: each level is spread evenly.

uint lghFirstLight(LghFrame frame) { return lgh.level[frame.startLevel - 1].offset; }
uint lghTopOffset(LghFrame frame) { return lgh.level[frame.topLevel - 1].offset; }
uint lghTopCount(LghFrame frame) { return lgh.level[frame.topLevel - 1].count; }
bool lghHasLights(LghFrame frame) {
  return frame.topLevel >= 1 && frame.startLevel <= frame.topLevel;
}

bool lghLightInTile(uint lightIndex, uint firstLight, int tile) {
  return int((lightIndex - firstLight) % uint(uInterleave * uInterleave)) == tile;
}

// ---- interleaved tiles ------------------------------------------------------------------------
// The tile atlas: n x n tiles of uTileSize pixels; full-resolution pixel p lives in tile p mod n
// at p / n. Without interleaving (n = 1) the atlas is the frame.
ivec2 lghAtlasPixel(ivec2 pixel) {
  ivec2 tile = pixel % uInterleave;
  return tile * uTileSize + pixel / uInterleave;
}

// The full-resolution pixel of an atlas pixel (may be outside the frame at the tiles' far edges).
ivec2 lghFramePixel(ivec2 atlasPixel, out int tileIndex) {
  ivec2 tile = atlasPixel / uTileSize;
  tileIndex = tile.x + uInterleave * tile.y;
  return (atlasPixel - tile * uTileSize) * uInterleave + tile;
}

bool lghInFrame(ivec2 pixel) { return all(lessThan(pixel, uFrameSize)) && all(greaterThanEqual(pixel, ivec2(0))); }

uint lghPixelIndex(ivec2 pixel) { return uint(pixel.y) * uint(uFrameSize.x) + uint(pixel.x); }

// ---- shadow samples ---------------------------------------------------------------------------
// Weight f_i of a light for shadow sampling: the luminance of its unshadowed contribution, for
// lights of levels >= uSampleStartLevel; 0 otherwise (never sampled).
float lghSampleWeight(GridLight light, vec3 radiance) {
  return int(light.level) >= uSampleStartLevel ? luminance(radiance) : 0.0;
}

// A pending sample slot (reservoirPendingSample) made final: position and weight. The position is
// the grid light's illumination centre, jittered by uShadowJitter times the paper's jitter (a box
// with the light's positional variance, reservoirJitter) and folded to the side of the centre the
// receiver is on. A grid light's VPLs lie on surfaces; a box around their centre reaches through
// those surfaces, and a shadow ray to a point behind one counts the light as occluded although its
// VPLs face the receiver: inside a closed sphere, where nothing occludes anything, the paper's
// jitter took 43% of the light away (docs/GI.md, "Shadow samples").
vec4 lghFinalSample(uint pixelSeed, vec4 pending, float runningSum, uint sampleIndex,
                    vec3 receiver) {
  if (pending.y <= 0.0) return vec4(0.0);
  uint lightIndex = floatBitsToUint(pending.x);
  GridLight light = gridLights[lightIndex];
  vec3 position = light.center;
  if (uShadowJitter > 0.0) {
    uint seed = reservoirLightSeed(pixelSeed, lightIndex);
    vec3 offset = (reservoirJitter(light.center, light.variance, seed, sampleIndex) - light.center) *
                  uShadowJitter;
    if (dot(offset, receiver - light.center) < 0.0) offset = -offset;
    position += offset;
  }
  return vec4(position, reservoirSampleWeight(runningSum, pending.y, uSampleCount));
}

#ifdef LGH_SAMPLE_STORAGE
// Per pixel: F in an r32f image, the k samples at shadowSamples[pixelIndex * k + s] (pending
// while lighting runs, final afterwards: vec4(position, weight)).
layout(r32f, binding = LGH_IMAGE_RESERVOIR_SUM) uniform coherent image2D uReservoirSum;
layout(std430, binding = LGH_BIND_SAMPLES) coherent buffer LghShadowSamples {
  vec4 shadowSamples[];
};
#endif

#ifdef LGH_OVERDRAW
layout(r32ui, binding = LGH_IMAGE_OVERDRAW) uniform uimage2D uOverdraw;
#endif

#ifdef LGH_RASTER_RESERVOIR
// The raster path streams lights into the reservoir from fragments of different draws and
// instances: additive blending cannot hold it, so F and the samples live in image/buffer memory
// and are updated read-modify-write. LGH_LOCK_MODE:
//   0  unlocked: the paper's default; fragments of one pixel that run at the same time may lose
//      an update (10-20% faster, results virtually identical - Sec. 4.1);
//   1  GL_ARB_fragment_shader_interlock, ordered: the update is a critical section in primitive
//      order (no deadlock possible); main() brackets it with LGH_INTERLOCK_BEGIN/END because the
//      interlock calls may only appear in main() outside flow control;
//   2  where interlock is missing: a per-pixel spin lock (imageAtomicCompSwap) with a bounded
//      number of attempts and the work done inside the loop - GPUs that do not schedule the
//      waiting fragment's lane independently would deadlock on an unbounded spin. A fragment that
//      gives up updates unlocked.
#ifndef LGH_LOCK_MODE
#define LGH_LOCK_MODE 0
#endif
#define LGH_SPIN_LIMIT 4096

#if LGH_LOCK_MODE == 1
#define LGH_INTERLOCK_BEGIN() beginInvocationInterlockARB()
#define LGH_INTERLOCK_END() endInvocationInterlockARB()
#else
#define LGH_INTERLOCK_BEGIN()
#define LGH_INTERLOCK_END()
#endif

#if LGH_LOCK_MODE == 2
layout(r32ui, binding = LGH_IMAGE_LOCK) uniform coherent uimage2D uReservoirLock;
#endif

void lghReservoirUpdate(ivec2 pixel, uint pixelIndex, uint lightIndex, float f) {
  float runningSum = imageLoad(uReservoirSum, pixel).r + f;
  imageStore(uReservoirSum, pixel, vec4(runningSum));
  uint seed = reservoirLightSeed(reservoirPixelSeed(uSeed, pixelIndex), lightIndex);
  uint mask = reservoirReplaceMask(f, runningSum, seed, uSampleCount);
  uint base = pixelIndex * uint(uSampleCount);
  for (int s = 0; s < uSampleCount; ++s) {
    if ((mask & (1u << uint(s))) != 0u) {
      shadowSamples[base + uint(s)] = reservoirPendingSample(lightIndex, f);
    }
  }
}

// Streams light `lightIndex` with weight f (> 0) into the pixel's reservoir.
void lghReservoirStream(ivec2 pixel, uint lightIndex, float f) {
  if (!(f > 0.0)) return;
  uint pixelIndex = lghPixelIndex(pixel);
#if LGH_LOCK_MODE == 2
  bool done = false;
  for (int attempt = 0; attempt < LGH_SPIN_LIMIT && !done; ++attempt) {
    if (imageAtomicCompSwap(uReservoirLock, pixel, 0u, 1u) == 0u) {
      lghReservoirUpdate(pixel, pixelIndex, lightIndex, f);
      memoryBarrier();
      imageAtomicExchange(uReservoirLock, pixel, 0u);
      done = true;
    }
  }
  if (!done) lghReservoirUpdate(pixel, pixelIndex, lightIndex, f);
#else
  lghReservoirUpdate(pixel, pixelIndex, lightIndex, f);
#endif
}
#endif  // LGH_RASTER_RESERVOIR

#endif
