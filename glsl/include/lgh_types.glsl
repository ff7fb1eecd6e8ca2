// Lighting Grid Hierarchy buffer layouts (std430). Mirrored in renderer/src/lightgrid/lgh_types.hpp,
// where static_asserts pin every size and offset; docs/LGH.md explains the fields.
//
// Public part (any shader may include it): PointLight (the build's input), GridLight (its output,
// all levels merged), LghLevelTable (per-level offsets, counts, cell sizes, grid origin and dims)
// and the draw-command indices. Consumers declare the blocks with their own bindings, e.g.
//   layout(std430, binding = 3) readonly buffer LghGridLights { GridLight gridLights[]; };
//   layout(std430, binding = 4) readonly buffer LghLevels { LghLevelTable lgh; };
//
// With LGH_BUILD_INTERNALS defined (the lgh_*.comp build kernels only) it also declares the
// builder's scratch buffers, their bindings (include/slots.glsl) and the helpers the kernels share.
#ifndef LGH_TYPES_GLSL
#define LGH_TYPES_GLSL

// Outside LGH_BUILD_INTERNALS: the shader library includes a file once, wherever it first appears.
#include "include/slots.glsl"

#define LGH_MAX_LEVELS 16

// One input point light: 32 bytes. The w components are ignored.
struct PointLight {
  vec4 positionPad;   // xyz: world position
  vec4 intensityPad;  // rgb: linear intensity, every component finite and >= 0
};

// One grid light of level >= 1: 48 bytes.
struct GridLight {
  vec3 center;      // illumination centre: the (trilinear weight x luminance)-weighted mean position
  uint level;       // 1..levelCount
  vec3 intensity;   // sum of w * rgb over the lights it represents
  uint vertex;      // its grid vertex in the level: x + dims.x * (y + dims.y * z)
  vec3 variance;    // per-axis weighted variance of the represented positions (world units^2)
  float luminance;  // luminance(intensity): the weight behind center and variance
};

// One level of the hierarchy: 48 bytes.
struct LghLevel {
  vec4 cell;         // x: cell size h_l = h_1 * 2^(l-1); y: 1 / h_l; zw: 0
  uvec4 dims;        // xyz: grid vertices per axis (the grid starts at the origin); w: x*y*z
  uint offset;       // index of the level's first grid light in the merged buffer
  uint count;        // |S_l|: grid lights of the level
  uint denseOffset;  // builder internal: the level's first vertex in the dense accumulators
  uint reserved;
};

// The level table ("LghLevels" SSBO): 912 bytes. Level l lives in level[l - 1].
struct LghLevelTable {
  vec4 originH1;      // xyz: grid origin (min corner of the lights' bounds); w: h_1
  vec4 boundsMaxTop;  // xyz: max corner of the lights' bounds; w: top cell size (longest edge)
  uint levelCount;    // L; 0 for an empty hierarchy (no lights, all dark, or invalid input)
  uint totalLights;   // grid lights over all levels
  uint inputCount;    // N, the lights given to the build
  uint contributingCount;  // valid lights with luminance > 0 (they set bounds and auto levels)
  uint invalidCount;  // lights with a non-finite or out-of-range position/intensity (> 0: empty)
  uint requestedLevels;    // 0: auto
  uint fitLevels;     // the most levels whose dense grids fit the builder's vertex budget
  uint overflow;      // 1 when grid lights were dropped for lack of output capacity
  float maxIntensity;   // largest rgb component of a contributing light
  float fixedScale;     // fixed-point atomics: value * fixedScale is accumulated as an integer
  float invFixedScale;
  uint flags;           // LGH_FLAG_*
  uint candidateS1[LGH_MAX_LEVELS];  // auto levels: |S1| had the hierarchy L = index + 1 levels
  LghLevel level[LGH_MAX_LEVELS];
};

#define LGH_FLAG_AUTO_LEVELS 1u
#define LGH_FLAG_FIXED_POINT 2u
#define LGH_FLAG_GATHER 4u

// DrawArraysIndirectCommand slots of the draw buffer (16 bytes each, 18 in all): instance i of a
// command draws grid light baseInstance + i (gl_BaseInstance + gl_InstanceID).
#define LGH_DRAW_FROM_START 0  // levels start..L (start: the build's drawStartLevel)
// 1..16: level l alone
#define LGH_DRAW_BELOW_TOP 17  // levels start..L-1 (the top level drawn full-screen instead)
#define LGH_DRAW_COMMANDS 18

#ifdef LGH_BUILD_INTERNALS
// ---- builder internals ------------------------------------------------------------------------
#include "include/common.glsl"

#define LGH_ROWS_PER_CHUNK 512      // S1 rows per work group in the cooperative gather
#define LGH_THREAD_GATHER_MAX 1000  // support volume (S1 vertices) up to which a thread gathers alone
#define LGH_THREAD_GATHER_MIN_VERTICES 16384u  // ... if the level has this many vertices
#define LGH_TAIL_VERTICES 4096u  // auto levels: candidates this small are left to one work group
#define LGH_MAX_COORD 1.0e30        // |position| and intensity limit: sums stay finite in float
#define LGH_BIN_SCAN_ITEMS 16u  // tile counts per thread in the one-group scan

struct LghBoundsPartial {
  vec4 minMaxC;  // xyz: min position, w: max intensity component
  vec4 maxPad;   // xyz: max position
  uvec4 counts;  // x: contributing lights, y: invalid lights
};

// One compacted S1 grid light as the gather reads it: 48 bytes, in S1 cell units so that the
// gather never subtracts large world coordinates.
struct LghS1Record {
  vec4 offsetLum;  // xyz: (centre - vertex) / h_1, in (-1, 1); w: luminance
  vec4 rgbX;       // rgb: intensity; w: vertex x (an integer < 2^24, exact as a float)
  vec4 varPad;     // xyz: variance / h_1^2
};

struct LghState {
  uvec4 dispatchArgs[LGH_DISPATCH_SLOTS];  // first: glDispatchComputeIndirect offsets = 16 * slot
  uvec4 gather[LGH_MAX_LEVELS];   // x: first group, y: groups, z: chunks per vertex (0: one thread
                                  // per vertex), w: rows box (by | bz << 16)
  uvec4 blocks[LGH_MAX_LEVELS];   // x: first compaction block, y: blocks
  uvec4 candDims[LGH_MAX_LEVELS];    // auto: S1 dims had the hierarchy L = index + 1 levels
  uvec4 candBitmap[LGH_MAX_LEVELS];  // auto: x = first word of its occupancy bitmap, y = words
  uint fineLevel;  // auto: the finest candidate (0: explicit levels or empty input)
  uint lightCount;
  uint bigSteps;   // auto: pyramid dispatches needed (<= LGH_PYRAMID_STEPS)
  uint tailFrom;   // auto: candidates <= tailFrom are built by the tail
  vec4 extentInvTop;  // xyz: bounds max - origin (float, as every kernel computes it); w: 1 / top
  // Work groups finished, for the last-group pattern (the last one resets its counter).
  uint boundsDone;
  uint markDone;
  uint compactDone;
  uint binDone;
  uvec4 binTiles;  // binned S1: xyz = tiles per axis, w = tiles (0 without levels)
};

// A light of the binned S1, in tile order: its level-1 grid coordinate as every kernel computes
// it (so the accumulation uses the very t its tile was chosen by), luminance and rgb. 32 bytes.
struct LghBinLight {
  vec4 tLum;  // xyz: t (lghGridCoordinate at level 1); w: luminance
  vec4 rgbPad;
};

// Kernels whose last work group reads what the other groups wrote (lgh_bounds.comp,
// lgh_compact_count.comp) define LGH_COHERENT; the others keep the L1-cached loads.
#ifdef LGH_COHERENT
#define LGH_SHARED_WRITES coherent
#else
#define LGH_SHARED_WRITES
#endif

layout(std430, binding = LGH_BIND_BUILD_LIGHTS) readonly buffer LghLights { PointLight lights[]; };
layout(std430, binding = LGH_BIND_BUILD_LEVELS) LGH_SHARED_WRITES buffer LghLevels { LghLevelTable lgh; };
layout(std430, binding = LGH_BIND_BUILD_STATE) LGH_SHARED_WRITES buffer LghStateBuffer { LghState st; };
layout(std430, binding = LGH_BIND_BUILD_PARTIALS) LGH_SHARED_WRITES buffer LghPartials { LghBoundsPartial partials[]; };
#ifdef LGH_FLOAT_ATOMICS
layout(std430, binding = LGH_BIND_BUILD_ACCUM) buffer LghAccum { float accum[]; };
#define LGH_ACCUM_STRIDE 9u
#else
layout(std430, binding = LGH_BIND_BUILD_ACCUM) buffer LghAccum { uint accum[]; };
#define LGH_ACCUM_STRIDE 18u
#endif
layout(std430, binding = LGH_BIND_BUILD_GRID_LIGHTS) writeonly buffer LghGridLights { GridLight gridLights[]; };
layout(std430, binding = LGH_BIND_BUILD_RECORDS) buffer LghRecords { LghS1Record s1Records[]; };
layout(std430, binding = LGH_BIND_BUILD_RANK) buffer LghRank { uint s1Rank[]; };
layout(std430, binding = LGH_BIND_BUILD_BITMAPS) LGH_SHARED_WRITES buffer LghBitmaps { uint bitmap[]; };
layout(std430, binding = LGH_BIND_BUILD_BLOCKS) LGH_SHARED_WRITES buffer LghBlocks { uint blockData[]; };
layout(std430, binding = LGH_BIND_BUILD_DRAWS) writeonly buffer LghDraws { uvec4 draws[]; };
// One bit per dense vertex: set by whoever accumulates into it, so the compaction reads (and
// clears) only touched vertices instead of streaming the whole dense grid twice.
layout(std430, binding = LGH_BIND_BUILD_TOUCHED) buffer LghTouched { uint touched[]; };
// Binned S1 (lgh_bin_*.comp, which define LGH_BINNED: Mesa counts declared blocks against the
// limit of 16 per compute shader, used or not). binCount: lights per tile, zero between builds
// (the bin scatter counts every light back down). binStart: tiles + 1 exclusive offsets.
// binItems: (tile, chunk) work items. binLights aliases the S1 records' buffer, which is only
// written after S1.
#ifdef LGH_BINNED
layout(std430, binding = LGH_BIND_BUILD_BIN_COUNT) LGH_SHARED_WRITES buffer LghBinCount { uint binCount[]; };
layout(std430, binding = LGH_BIND_BUILD_BIN_START) LGH_SHARED_WRITES buffer LghBinStart { uint binStart[]; };
layout(std430, binding = LGH_BIND_BUILD_BIN_ITEMS) LGH_SHARED_WRITES buffer LghBinItems { uvec2 binItems[]; };
layout(std430, binding = LGH_BIND_BUILD_RECORDS) buffer LghBinLights { LghBinLight binLights[]; };
#endif

// Non-finite test on the bit pattern: drivers may fold isnan/isinf away under fast math.
bool lghFinite(float x) { return (floatBitsToUint(x) & 0x7f800000u) != 0x7f800000u; }

bool lghValidLight(vec3 p, vec3 c) {
  for (int a = 0; a < 3; ++a) {
    if (!lghFinite(p[a]) || !lghFinite(c[a])) return false;
    if (abs(p[a]) > LGH_MAX_COORD || c[a] < 0.0 || c[a] > LGH_MAX_COORD) return false;
  }
  return true;
}

uint lghCeilDiv(uint a, uint b) { return (a + b - 1u) / b; }

// Work groups for `items` groups of work: 2D when over the 65535 limit of one dimension. The
// kernel linearizes with lghGroupIndex() and stops at `items` (kept in w).
uvec4 lghDispatch(uint groups) {
  uint x = min(groups, 65535u);
  return uvec4(x, groups == 0u ? 0u : lghCeilDiv(groups, 65535u), 1u, groups);
}
uint lghGroupIndex() { return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x; }
// For kernels with a last-group epilogue: at least one group even without items.
uvec4 lghDispatchAtLeastOne(uint groups) {
  uvec4 args = lghDispatch(groups);
  return uvec4(max(args.x, 1u), max(args.y, 1u), 1u, groups);
}

// Grid vertices per axis of a grid whose longest axis has 2^e cells (level l of an L-level
// hierarchy: e = L - l). Kernels map a position to grid units with exactly these float operations,
// so a light never lands outside: t = min((p - origin) * invH, 2^e).
uvec3 lghGridDims(uint e) {
  float cells = float(1u << e);
  precise vec3 t = st.extentInvTop.xyz * (st.extentInvTop.w * cells);
  return uvec3(ceil(min(t, vec3(cells)))) + 1u;
}

// Vertex count with overflow guard: returns 0xffffffff when over 2^31.
uint lghVertexCount(uvec3 dims) {
  float product = float(dims.x) * float(dims.y) * float(dims.z);
  return product > 2147483648.0 ? 0xffffffffu : dims.x * dims.y * dims.z;
}

uint lghAlignBlock(uint n) { return lghCeilDiv(n, LGH_BLOCK) * LGH_BLOCK; }

// Grid coordinates (x fastest) of a linear vertex index.
uvec3 lghDecode(uint index, uvec3 dims) {
  uint plane = dims.x * dims.y;
  uint z = index / plane;
  uint rest = index - z * plane;
  uint y = rest / dims.x;
  return uvec3(rest - y * dims.x, y, z);
}

uint lghEncode(uvec3 v, uvec3 dims) { return v.x + dims.x * (v.y + dims.y * v.z); }

// ---- work-group scans and reductions ------------------------------------------------------------
// Three barriers: 16 threads each walk a segment of 16 values, then one thread walks the 16
// segment sums (a Hillis-Steele tree needs 16 barriers for the same 256 values).
shared uint s_lghScan[LGH_GROUP];
shared uint s_lghSegments[LGH_GROUP / 16];
shared uint s_lghTotal;

// Exclusive prefix sum of `value` over the work group, in thread order; `total` gets the sum.
uint lghGroupExclusiveScan(uint value, out uint total) {
  const uint tid = gl_LocalInvocationID.x;
  s_lghScan[tid] = value;
  barrier();
  if (tid < LGH_GROUP / 16u) {
    uint sum = 0u;
    for (uint i = 0u; i < 16u; ++i) {
      uint v = s_lghScan[tid * 16u + i];
      s_lghScan[tid * 16u + i] = sum;
      sum += v;
    }
    s_lghSegments[tid] = sum;
  }
  barrier();
  if (tid == 0u) {
    uint sum = 0u;
    for (uint i = 0u; i < LGH_GROUP / 16u; ++i) {
      uint v = s_lghSegments[i];
      s_lghSegments[i] = sum;
      sum += v;
    }
    s_lghTotal = sum;
  }
  barrier();
  const uint result = s_lghScan[tid] + s_lghSegments[tid / 16u];
  total = s_lghTotal;
  barrier();  // the arrays may be reused right away
  return result;
}

// ---- last work group -------------------------------------------------------------------------------
// Fuses a one-group epilogue into a kernel instead of a dependent dispatch (each costs a GPU-wide
// drain and refill): every group publishes its result, fences it, and counts itself done; the group that
// counts last sees every result (the buffers it reads are coherent) and runs the epilogue.
// Every group of the dispatch must call this exactly once, in uniform control flow.
shared bool s_lghLast;

bool lghFinishLastGroup(uint counterIndex) {
  memoryBarrierBuffer();
  barrier();
  if (gl_LocalInvocationID.x == 0u) {
    uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_NumWorkGroups.z;
    uint done;
    if (counterIndex == 0u) done = atomicAdd(st.boundsDone, 1u);
    else if (counterIndex == 1u) done = atomicAdd(st.markDone, 1u);
    else if (counterIndex == 2u) done = atomicAdd(st.compactDone, 1u);
    else done = atomicAdd(st.binDone, 1u);
    s_lghLast = done == groups - 1u;
  }
  barrier();
  if (!s_lghLast) return false;
  memoryBarrierBuffer();
  if (gl_LocalInvocationID.x == 0u) {
    if (counterIndex == 0u) st.boundsDone = 0u;
    else if (counterIndex == 1u) st.markDone = 0u;
    else if (counterIndex == 2u) st.compactDone = 0u;
    else st.binDone = 0u;
  }
  return true;
}

// ---- bounds reduction (lgh_bounds.comp) ---------------------------------------
// Each thread folds its share, then one shared-memory atomic per quantity: float min/max through
// order-preserving integer keys. (A shared-array tree of vec4s compiled for over ten seconds on
// llvmpipe; the atomics compile in well under one.)
shared uint s_lghLo[3];
shared uint s_lghHi[3];
shared uint s_lghMaxC;
shared uint s_lghContributing;
shared uint s_lghInvalid;

uint lghOrderedKey(float f) {
  uint bits = floatBitsToUint(f);
  return (bits & 0x80000000u) != 0u ? ~bits : (bits | 0x80000000u);
}
float lghFromOrderedKey(uint key) {
  return uintBitsToFloat((key & 0x80000000u) != 0u ? (key & 0x7fffffffu) : ~key);
}

void lghBoundsBegin() {
  if (gl_LocalInvocationID.x == 0u) {
    for (int a = 0; a < 3; ++a) {
      s_lghLo[a] = 0xffffffffu;
      s_lghHi[a] = 0u;
    }
    s_lghMaxC = 0u;
    s_lghContributing = 0u;
    s_lghInvalid = 0u;
  }
  barrier();
}

void lghBoundsAdd(LghBoundsPartial p) {
  if (p.counts.x > 0u) {
    for (int a = 0; a < 3; ++a) {
      atomicMin(s_lghLo[a], lghOrderedKey(p.minMaxC[a]));
      atomicMax(s_lghHi[a], lghOrderedKey(p.maxPad[a]));
    }
    atomicMax(s_lghMaxC, floatBitsToUint(max(p.minMaxC.w, 0.0)));
    atomicAdd(s_lghContributing, p.counts.x);
  }
  if (p.counts.y > 0u) atomicAdd(s_lghInvalid, p.counts.y);
}

// After a barrier: the work group's result.
LghBoundsPartial lghBoundsResult() {
  LghBoundsPartial p;
  p.counts = uvec4(s_lghContributing, s_lghInvalid, 0u, 0u);
  p.minMaxC = vec4(3.0e38, 3.0e38, 3.0e38, uintBitsToFloat(s_lghMaxC));
  p.maxPad = vec4(-3.0e38, -3.0e38, -3.0e38, 0.0);
  if (p.counts.x > 0u) {
    for (int a = 0; a < 3; ++a) {
      p.minMaxC[a] = lghFromOrderedKey(s_lghLo[a]);
      p.maxPad[a] = lghFromOrderedKey(s_lghHi[a]);
    }
  }
  return p;
}

// ---- dense accumulators: 9 values per grid vertex ---------------------------------------------
// [0..2] sum w*rgb, [3..5] sum w*I*u, [6..8] sum w*I*(u^2 + var/h^2), with u = (p - vertex) / h in
// cell units. Float atomics where GL_NV_shader_atomic_float exists; else 64-bit fixed point from
// two 32-bit atomics (low word, then the high word with the carry): exact, order-independent sums
// of values rounded to multiples of 1/fixedScale (see docs/LGH.md for the precision).
// The builder puts "#extension GL_NV_shader_atomic_float : require" and "#define
// LGH_FLOAT_ATOMICS" right after #version (an #extension must precede all other tokens).
#ifdef LGH_FLOAT_ATOMICS
void lghAdd(uint slot, float value) {
  if (value != 0.0) atomicAdd(accum[slot], value);
}
float lghRead(uint slot) { return accum[slot]; }
void lghClear(uint vertex) {
  for (uint k = 0u; k < 9u; ++k) accum[vertex * 9u + k] = 0.0;
}
#else
// value * fixedScale rounded to an integer, as a 64-bit two's complement (lo, hi); (0, 0) for 0.
// `precise`: no fused multiply-add, so every kernel rounds a value alike (the binned and the
// direct S1 give bit-identical sums).
uvec2 lghFixedSplit(float value) {
  precise float x = floor(value * lgh.fixedScale + 0.5);
  if (x == 0.0) return uvec2(0u);
  // |x| = hi * 2^32 + lo exactly (|x| carries at most 24 significant bits, so both parts do);
  // then the 64-bit two's complement for negative x (2^32 - lo would not fit a float).
  float magnitude = abs(x);
  float hiF = floor(magnitude * (1.0 / 4294967296.0));
  uint lo = uint(magnitude - hiF * 4294967296.0);
  uint hi = uint(hiF);
  if (x < 0.0) {
    hi = ~hi + (lo == 0u ? 1u : 0u);
    lo = 0u - lo;
  }
  return uvec2(lo, hi);
}
// Adds a 64-bit (lo, hi): the low word, the carry out of it from the returned old value, the
// high word (skipped when zero). Exact modulo 2^64, whatever the order of the adds.
void lghAddFixed(uint slot, uvec2 x) {
  if (x == uvec2(0u)) return;
  uint old = atomicAdd(accum[2u * slot], x.x);
  uint hi = x.y + ((old + x.x < old) ? 1u : 0u);
  if (hi != 0u) atomicAdd(accum[2u * slot + 1u], hi);
}
void lghAdd(uint slot, float value) { lghAddFixed(slot, lghFixedSplit(value)); }
float lghRead(uint slot) {
  uint lo = accum[2u * slot];
  int hi = int(accum[2u * slot + 1u]);
  return (float(hi) * 4294967296.0 + float(lo)) * lgh.invFixedScale;
}
void lghClear(uint vertex) {
  for (uint k = 0u; k < 18u; ++k) accum[vertex * 18u + k] = 0u;
}
#endif

void lghTouch(uint vertex) {
  const uint word = vertex >> 5;
  const uint bit = 1u << (vertex & 31u);
  if ((touched[word] & bit) == 0u) atomicOr(touched[word], bit);
}

bool lghTouched(uint vertex) { return (touched[vertex >> 5] & (1u << (vertex & 31u))) != 0u; }

void lghAccumulate(uint vertex, vec3 rgb, vec3 moment1, vec3 moment2) {
  uint base = vertex * 9u;
  for (int k = 0; k < 3; ++k) {
    lghAdd(base + uint(k), rgb[k]);
    lghAdd(base + 3u + uint(k), moment1[k]);
    lghAdd(base + 6u + uint(k), moment2[k]);
  }
  lghTouch(vertex);
}

vec3 lghReadRgb(uint vertex) {
  uint base = vertex * 9u;
  return vec3(lghRead(base), lghRead(base + 1u), lghRead(base + 2u));
}

// An occupied vertex: touched, with an accumulated luminance > 0. (Fixed point can round a touched
// vertex's rgb to zero; it is then cleared but not emitted.)
bool lghOccupied(uint vertex) { return lghTouched(vertex) && luminance(lghReadRgb(vertex)) > 0.0; }

// ---- a light's share of its cell's corners (the scatter and the binned S1) ----------------------
// Grid coordinate of p at level l, exactly as every kernel and the CPU reference compute it.
vec3 lghGridCoordinate(vec3 p, uint l) {
  const float cells = float(1u << (lgh.levelCount - l));
  precise vec3 t = min((p - lgh.originH1.xyz) * lgh.level[l - 1u].cell.y, vec3(cells));
  return t;
}

// The share of corner `corner` (bit 0: +x, bit 1: +y, bit 2: +z) of the cell floor(t) of a light
// at grid coordinate t: w * rgb, w I u and w I u^2 with u = (t - vertex) in (-1, 1) and the
// trilinear weight w. False (and nothing to add) for a zero weight: a light on a grid plane
// touches 4, 2 or 1 vertices.
bool lghCornerShare(vec3 t, vec3 rgb, float lum, uint corner, out uvec3 vertex, out vec3 wRgb,
                    out vec3 moment1, out vec3 moment2) {
  const vec3 i0 = floor(t);
  const vec3 f = t - i0;
  const bvec3 high = bvec3((corner & 1u) != 0u, (corner & 2u) != 0u, (corner & 4u) != 0u);
  const vec3 axisWeight = mix(1.0 - f, f, high);
  const float w = axisWeight.x * axisWeight.y * axisWeight.z;
  vertex = uvec3(i0) + uvec3(high);
  const vec3 u = mix(f, f - 1.0, high);
  const float wi = w * lum;
  wRgb = w * rgb;
  moment1 = wi * u;
  moment2 = wi * u * u;
  return w > 0.0;
}

// ---- binned S1 ------------------------------------------------------------------------------------
// Tile edge T in S1 cells; lgh_bin_accum.comp sizes its shared memory with the same constants.
uint lghBinTile() {
  return (lgh.flags & LGH_FLAG_FIXED_POINT) != 0u ? LGH_BIN_TILE_FIXED : LGH_BIN_TILE_FLOAT;
}

// The tile of the cell floor(t) (level-1 t). A light at t = dims - 1 exactly (the upper bounds,
// when T divides the cells) belongs to the last tile: its cell lies outside, but it only touches
// the vertex dims - 1, the last tile's upper corner.
uint lghBinIndex(vec3 t) {
  const uvec3 tile = min(uvec3(floor(t)) / lghBinTile(), st.binTiles.xyz - 1u);
  return lghEncode(tile, st.binTiles.xyz);
}

// The level (1-based) whose dense range holds dense vertex `d`; 0 if none.
uint lghLevelOfDense(uint d) {
  for (uint l = 1u; l <= lgh.levelCount; ++l) {
    LghLevel level = lgh.level[l - 1u];
    if (d >= level.denseOffset && d < level.denseOffset + lghAlignBlock(level.dims.w)) return l;
  }
  return 0u;
}

// ---- level configuration (one thread) -----------------------------------------------------------
// Loops over levels run to u_levelLimit (= LGH_MAX_LEVELS, set by the builder) rather than the
// constant: a bound the compiler cannot see keeps it from unrolling them (llvmpipe spent tens of
// seconds compiling the unrolled setup kernel).
uniform uint u_levelLimit;
// Work of the gather for level l >= 2: a level-l vertex reads the S1 vertices within s = 2^(l-1)
// S1 cells of it, a box of (2s+1)^3 clipped to the grid. Small boxes: one thread per vertex;
// larger ones: a work group per (vertex, chunk of LGH_ROWS_PER_CHUNK x-rows), reduced in shared
// memory and added atomically (few adds per vertex, so no contention).
uvec4 lghGatherWork(uint l) {
  uint s = 1u << (l - 1u);
  uvec3 box = min(uvec3(2u * s + 1u), lgh.level[0].dims.xyz);
  uint rows = box.y * box.z;
  uint vertices = lgh.level[l - 1u].dims.w;
  uint packedBox = box.y | (box.z << 16);
  // One thread per vertex only when there are enough vertices to fill the GPU; otherwise a few
  // long serial threads set the pace.
  if (box.x * rows <= LGH_THREAD_GATHER_MAX && vertices >= LGH_THREAD_GATHER_MIN_VERTICES) {
    return uvec4(0u, lghCeilDiv(vertices, LGH_GROUP), 0u, packedBox);
  }
  uint chunks = lghCeilDiv(rows, LGH_ROWS_PER_CHUNK);
  return uvec4(0u, vertices * chunks, chunks, packedBox);
}

// Writes the level table and every dispatch argument that depends on it for an L-level
// hierarchy (L = 0: empty). Level l has 2^(L-l) cells along the longest axis.
void lghConfigure(uint L) {
  const float top = lgh.boundsMaxTop.w;
  lgh.levelCount = L;
  lgh.originH1.w = L > 0u ? ldexp(top, 1 - int(L)) : 0.0;
  uint dense = 0u;
  for (uint l = 1u; l <= u_levelLimit; ++l) {
    LghLevel level = LghLevel(vec4(0.0), uvec4(0u), 0u, 0u, 0u, 0u);
    uvec4 blocks = uvec4(0u);
    if (l <= L) {
      uint e = L - l;
      uvec3 dims = lghGridDims(e);
      uint n = dims.x * dims.y * dims.z;
      level.cell = vec4(ldexp(top, -int(e)), st.extentInvTop.w * float(1u << e), 0.0, 0.0);
      level.dims = uvec4(dims, n);
      level.denseOffset = dense;
      blocks = uvec4(dense / LGH_BLOCK, lghCeilDiv(n, LGH_BLOCK), 0u, 0u);
      dense += lghAlignBlock(n);
    }
    lgh.level[l - 1u] = level;
    st.blocks[l - 1u] = blocks;
    uint scatterGroups = l <= L ? lghCeilDiv(st.lightCount, LGH_GROUP) : 0u;
    st.dispatchArgs[LGH_SLOT_SCATTER + l] = lghDispatch(scatterGroups);
  }
  // Binned S1: max(1, ceil(cells / T)) tiles per axis (a flat axis has 0 cells and one tile).
  uvec4 binTiles = uvec4(0u);
  if (L > 0u) {
    const uint tileCells = lghBinTile();
    uvec3 tiles = max((lgh.level[0].dims.xyz - 1u + tileCells - 1u) / tileCells, uvec3(1u));
    binTiles = uvec4(tiles, tiles.x * tiles.y * tiles.z);
  }
  st.binTiles = binTiles;
  uint blocksAll = dense / LGH_BLOCK;
  uint blocksS1 = L > 0u ? lghAlignBlock(lgh.level[0].dims.w) / LGH_BLOCK : 0u;
  st.dispatchArgs[LGH_SLOT_COMPACT_S1] = lghDispatchAtLeastOne(blocksS1);
  st.dispatchArgs[LGH_SLOT_COMPACT_REST] = lghDispatchAtLeastOne(blocksAll - blocksS1);
  st.dispatchArgs[LGH_SLOT_COMPACT_ALL] = lghDispatchAtLeastOne(blocksAll);
  uint groups = 0u;
  st.gather[0] = uvec4(0u);
  for (uint l = 2u; l <= u_levelLimit; ++l) {
    uvec4 work = uvec4(0u);
    if (l <= L) {
      work = lghGatherWork(l);
      work.x = groups;
      groups += work.y;
    }
    st.gather[l - 1u] = work;
    st.dispatchArgs[LGH_SLOT_GATHER + l] = lghDispatch(work.y);
  }
  st.dispatchArgs[LGH_SLOT_GATHER_ALL] = lghDispatch(groups);
}

#endif  // LGH_BUILD_INTERNALS
#endif  // LGH_TYPES_GLSL
