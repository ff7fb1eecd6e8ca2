#version 450 core
// LGH compute lighting: the same hierarchy, blending, BRDF and reservoir as the raster path
// (glsl/lgh_light_volume.*), for GPUs whose rasterizers are weak next to their compute units.
//
// One work group shades an 8x8 block of pixels of one interleave tile (without interleaving: of
// the frame). It
//  1. reduces the world-space bounding box of its pixels' G-buffer positions (shared atomics);
//  2. per level below the top, finds the grid lights whose sphere of radius 2 r_l can reach the
//     box: the level's lights are sorted by grid vertex (the build's compaction keeps vertex
//     order), so the lights whose vertices lie in the box grown by 2 r_l + h_l (a light's centre
//     is within one cell of its vertex) are, per (y, z) row of the grid, one contiguous run found
//     by two binary searches. Runs are visited row by row: the lights arrive in buffer order, as
//     the raster path draws them, so both paths stream the same lights in the same order into
//     the reservoir and make the same choices;
//  3. loads each batch of 64 candidates into shared memory, keeps those whose sphere touches the
//     box and whose inner radius r_(l-1) (blending weight 0 inside, l > start) does not hold it
//     whole, and lets every pixel loop over them;
//  4. ends with the top level, one run of at most 8 lights that only the inner radius culls, and
//     writes radiance, F and the final shadow samples - the thread owns its pixel's reservoir,
//     so no locks.
// With interleaving each tile only visits its own lights (light j goes to tile j mod n^2), and
// the output goes to the tile atlas for the compositing pass shared with the raster path.
//
// Defines: LGH_SAMPLES (k, 1..8), LGH_DIRECT_OUTPUT (no interleave: write the rgba16f indirect
// target; else the rgba32f atlas), LGH_OVERDRAW (count lights evaluated per pixel).
// Inputs: G-buffer (units 0..4), grid lights, level table.
// Outputs: radiance image, reservoir sum image, shadow-sample buffer, [overdraw counter].

#define LGH_SAMPLE_STORAGE
#include "include/gbuffer.glsl"
#include "include/lgh_shading.glsl"

#define TILE 8
#define GROUP 64

layout(local_size_x = TILE, local_size_y = TILE) in;

#ifdef LGH_DIRECT_OUTPUT
layout(rgba16f, binding = LGH_IMAGE_OUTPUT) uniform writeonly image2D uOutput;
#else
layout(rgba32f, binding = LGH_IMAGE_OUTPUT) uniform writeonly image2D uOutput;
#endif

shared uint s_boxKeys[6];      // the block's box: min xyz, max xyz as ordered integer keys
shared uint s_runStart[GROUP];  // first light of each row's run (of this tile's lights)
shared uint s_runScan[GROUP];   // inclusive prefix sum of the runs' lengths
// A batch of candidates: what the pixels' loop reads of each, in two 16-byte loads. As integers,
// so that no hash or index passes through a float register (a NaN's bits need not survive one).
shared uvec4 s_centerHash[GROUP];      // xyz: centre (float bits); w: reservoirLightHash(index)
shared uvec4 s_intensityIndex[GROUP];  // xyz: intensity (float bits); w: the light's index
shared uint s_keep[GROUP];

// The pixel an invocation shades and its reservoir.
struct Pixel {
  SurfacePoint surface;
  bool valid;
  vec3 toViewer;
  vec3 radiance;
  uint seed;
  uint evaluated;
  float runningSum;
  uint sampleLight[LGH_SAMPLES];
  float sampleWeight[LGH_SAMPLES];
};

// The block's bounding box and what culling a level against it needs.
struct Block {
  vec3 boxMin;
  vec3 boxMax;
  int tile;
  uint tiles;
  uint firstLight;
};

// What every light of one level shares: its blending, and whether shadow sampling uses it.
struct LevelStream {
  LghLevelBlend blend;
  bool sampled;  // level >= uSampleStartLevel (lghSampleWeight)
};

// Candidate i of the batch in shared memory, one light of `level`, into the pixel's sum and
// reservoir: what lghGridLightRadiance and lghSampleWeight give, with the level's terms and the
// light's hash computed once per batch instead of once per pixel.
void streamLight(inout Pixel px, uint i, LevelStream level, LghFrame frame) {
  ++px.evaluated;
  uvec4 centerHash = s_centerHash[i];
  uvec4 intensityIndex = s_intensityIndex[i];
  float blend;
  vec3 radiance = lghGridLightRadianceAt(px.surface, px.toViewer, uintBitsToFloat(centerHash.xyz),
                                         uintBitsToFloat(intensityIndex.xyz), level.blend,
                                         frame.minDistance2, blend);
  if (blend <= 0.0) return;
  px.radiance += radiance;
  if (!level.sampled) return;
  float f = luminance(radiance);
  if (!(f > 0.0)) return;
  px.runningSum += f;
  uint index = intensityIndex.w;
  uint seed = reservoirLightSeedOfHash(px.seed, centerHash.w);
  uint mask = reservoirReplaceMask(f, px.runningSum, seed, LGH_SAMPLES);
  for (int s = 0; s < LGH_SAMPLES; ++s) {
    if ((mask & (1u << uint(s))) != 0u) {
      px.sampleLight[s] = index;
      px.sampleWeight[s] = f;
    }
  }
}

// Floats as unsigned integers of the same order, for shared-memory atomicMin/Max (a shared-array
// tree reduction of vectors takes llvmpipe seconds to compile; the atomics do not).
uint orderedKey(float f) {
  uint bits = floatBitsToUint(f);
  return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

float fromOrderedKey(uint key) {
  return uintBitsToFloat((key & 0x80000000u) != 0u ? key & 0x7fffffffu : ~key);
}

// The block's bounding box; false when no pixel has geometry.
bool reduceBounds(uint tid, Pixel px, out vec3 boxMin, out vec3 boxMax) {
  if (tid < 3u) {
    s_boxKeys[tid] = 0xffffffffu;
    s_boxKeys[tid + 3u] = 0u;
  }
  barrier();
  if (px.valid) {
    for (uint a = 0u; a < 3u; ++a) {
      atomicMin(s_boxKeys[a], orderedKey(px.surface.position[a]));
      atomicMax(s_boxKeys[a + 3u], orderedKey(px.surface.position[a]));
    }
  }
  barrier();
  bool any = s_boxKeys[0] != 0xffffffffu;
  boxMin = vec3(fromOrderedKey(s_boxKeys[0]), fromOrderedKey(s_boxKeys[1]),
                fromOrderedKey(s_boxKeys[2]));
  boxMax = vec3(fromOrderedKey(s_boxKeys[3]), fromOrderedKey(s_boxKeys[4]),
                fromOrderedKey(s_boxKeys[5]));
  barrier();
  return any;
}

// First light in [first, last) of a level whose vertex is >= vertex.
uint lowerBound(uint first, uint last, uint vertex) {
  while (first < last) {
    uint mid = (first + last) >> 1u;
    if (gridLights[mid].vertex < vertex) {
      first = mid + 1u;
    } else {
      last = mid;
    }
  }
  return first;
}

// Inclusive Hillis-Steele scan of s_runScan.
void scanRuns(uint tid) {
  for (uint stride = 1u; stride < GROUP; stride <<= 1u) {
    uint add = tid >= stride ? s_runScan[tid - stride] : 0u;
    barrier();
    s_runScan[tid] += add;
    barrier();
  }
}

// The run that holds stream position p: the first with s_runScan[run] > p.
uint runOf(uint p) {
  uint first = 0u;
  uint last = GROUP;
  while (first < last) {
    uint mid = (first + last) >> 1u;
    if (s_runScan[mid] <= p) {
      first = mid + 1u;
    } else {
      last = mid;
    }
  }
  return first;
}

bool sphereTouchesBox(vec3 center, float radius, vec3 boxMin, vec3 boxMax) {
  vec3 outside = max(max(boxMin - center, center - boxMax), vec3(0.0));
  return dot(outside, outside) <= radius * radius;
}

bool boxInsideSphere(vec3 center, float radius, vec3 boxMin, vec3 boxMax) {
  vec3 farthest = max(abs(boxMin - center), abs(boxMax - center));
  return dot(farthest, farthest) < radius * radius;
}

struct LevelRange {
  ivec3 lo;
  ivec3 hi;
  bool empty;
};

// Grid vertices whose lights can reach the box: their centres lie within one cell of them.
LevelRange levelRange(LghLevel level, float reach, Block block) {
  vec3 origin = lgh.originH1.xyz;
  float invH = level.cell.y;
  vec3 last = vec3(level.dims.xyz) - 1.0;
  vec3 lo = floor((block.boxMin - reach - origin) * invH) - 1.0;
  vec3 hi = ceil((block.boxMax + reach - origin) * invH) + 1.0;
  LevelRange range;
  range.empty = any(lessThan(hi, vec3(0.0))) || any(greaterThan(lo, last));
  range.lo = ivec3(clamp(lo, vec3(0.0), last));
  range.hi = ivec3(clamp(hi, vec3(0.0), last));
  return range;
}

// The lights [a, b) of this block's tile: those congruent to the tile mod n^2.
void setRun(uint slot, uint a, uint b, Block block) {
  uint aligned = a + (uint(block.tile) + block.tiles - (a - block.firstLight) % block.tiles) % block.tiles;
  s_runStart[slot] = aligned;
  s_runScan[slot] = aligned < b ? (b - aligned + block.tiles - 1u) / block.tiles : 0u;
}

// Row `row` of the level's vertex box: one run of the vertex-sorted level.
void setRowRun(uint slot, uint row, LghLevel level, LevelRange range, Block block) {
  uint rowsY = uint(range.hi.y - range.lo.y + 1);
  uint y = uint(range.lo.y) + row % rowsY;
  uint z = uint(range.lo.z) + row / rowsY;
  uint rowVertex = level.dims.x * (y + level.dims.y * z);
  uint levelEnd = level.offset + level.count;
  uint a = lowerBound(level.offset, levelEnd, rowVertex + uint(range.lo.x));
  uint b = lowerBound(a, levelEnd, rowVertex + uint(range.hi.x) + 1u);
  setRun(slot, a, b, block);
}

// Streams the lights of the runs in s_runStart / s_runScan (scanned) through shared memory.
void shadeRuns(inout Pixel px, uint tid, int level, LghFrame frame, Block block) {
  LevelStream stream;
  stream.blend = lghLevelBlend(level, frame.startLevel, frame.topLevel, frame.alpha, frame.h1);
  stream.sampled = level >= uSampleStartLevel;
  float r = stream.blend.radius;
  float reach = level == frame.topLevel ? 3.0e38 : 2.0 * r;
  float hole = level > frame.startLevel ? 0.5 * r : 0.0;
  uint total = s_runScan[GROUP - 1u];
  for (uint batch = 0u; batch < total; batch += GROUP) {
    uint p = batch + tid;
    uint keep = 0u;
    if (p < total) {
      uint run = runOf(p);
      uint before = run > 0u ? s_runScan[run - 1u] : 0u;
      uint index = s_runStart[run] + (p - before) * block.tiles;
      GridLight light = gridLights[index];
      bool reaches = sphereTouchesBox(light.center, reach, block.boxMin, block.boxMax) &&
                     !boxInsideSphere(light.center, hole, block.boxMin, block.boxMax);
      keep = reaches ? 1u : 0u;
      s_centerHash[tid] = uvec4(floatBitsToUint(light.center), reservoirLightHash(index));
      s_intensityIndex[tid] = uvec4(floatBitsToUint(light.intensity), index);
    }
    s_keep[tid] = keep;
    barrier();
    uint count = min(uint(GROUP), total - batch);
    if (px.valid) {
      for (uint i = 0u; i < count; ++i) {
        if (s_keep[i] != 0u) streamLight(px, i, stream, frame);
      }
    }
    barrier();
  }
}

// Level l's lights that can reach the block, 64 rows of its vertex box at a time; the top level
// is one run.
void shadeLevel(inout Pixel px, uint tid, int l, LghFrame frame, Block block) {
  LghLevel level = lgh.level[l - 1];
  if (level.count == 0u) return;
  bool top = l == frame.topLevel;
  LevelRange range = levelRange(level, 2.0 * lghRadius(l, frame.alpha, frame.h1), block);
  if (!top && range.empty) return;
  uint rows = top ? 1u
                  : uint(range.hi.y - range.lo.y + 1) * uint(range.hi.z - range.lo.z + 1);
  for (uint rowBase = 0u; rowBase < rows; rowBase += GROUP) {
    uint row = rowBase + tid;
    if (row >= rows) {
      setRun(tid, 0u, 0u, block);
    } else if (top) {
      setRun(tid, level.offset, level.offset + level.count, block);
    } else {
      setRowRun(tid, row, level, range, block);
    }
    barrier();
    scanRuns(tid);
    shadeRuns(px, tid, l, frame, block);
    barrier();
  }
}

void writeOutputs(Pixel px, ivec2 pixel, ivec2 atlasPixel) {
  vec4 radiance = vec4(px.radiance, px.valid ? 1.0 : 0.0);
#ifdef LGH_DIRECT_OUTPUT
  imageStore(uOutput, pixel, radiance);
#else
  imageStore(uOutput, atlasPixel, radiance);
#endif
  imageStore(uReservoirSum, pixel, vec4(px.runningSum));
  uint base = lghPixelIndex(pixel) * uint(LGH_SAMPLES);
  // A loop the compiler keeps (uSampleCount == LGH_SAMPLES): it runs once per pixel.
  for (int s = 0; s < min(uSampleCount, LGH_SAMPLES); ++s) {
    vec4 pending = reservoirPendingSample(px.sampleLight[s], px.sampleWeight[s]);
    shadowSamples[base + uint(s)] =
        lghFinalSample(px.seed, pending, px.runningSum, uint(s), px.surface.position);
  }
#ifdef LGH_OVERDRAW
  imageStore(uOverdraw, pixel, uvec4(px.evaluated));
#endif
}

Pixel loadPixel(ivec2 pixel) {
  Pixel px;
  px.surface = defaultSurface(vec3(0.0), vec3(0.0, 0.0, 1.0), vec3(0.0), 0.0, 1.0, 1.0);
  px.valid = lghInFrame(pixel) && readSurface(pixel, px.surface);
  px.toViewer = px.valid ? normalize(uCameraPosition - px.surface.position) : vec3(0.0, 0.0, 1.0);
  px.radiance = vec3(0.0);
  px.seed = reservoirPixelSeed(uSeed, lghPixelIndex(pixel));
  px.evaluated = 0u;
  px.runningSum = 0.0;
  for (int s = 0; s < LGH_SAMPLES; ++s) {
    px.sampleLight[s] = 0u;
    px.sampleWeight[s] = 0.0;
  }
  return px;
}

void main() {
  uint tid = gl_LocalInvocationIndex;
  Block block;
  block.tile = int(gl_WorkGroupID.z);
  block.tiles = uint(uInterleave * uInterleave);
  ivec2 tileXY = ivec2(block.tile % uInterleave, block.tile / uInterleave);
  ivec2 tilePixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 pixel = tilePixel * uInterleave + tileXY;
  Pixel px = loadPixel(pixel);
  LghFrame frame = lghFrame();
  if (reduceBounds(tid, px, block.boxMin, block.boxMax) && lghHasLights(frame)) {
    block.firstLight = lghFirstLight(frame);
    for (int l = frame.startLevel; l <= frame.topLevel; ++l) shadeLevel(px, tid, l, frame, block);
  }
  if (lghInFrame(pixel)) writeOutputs(px, pixel, tileXY * uTileSize + tilePixel);
}
