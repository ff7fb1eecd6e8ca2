#version 450
// LGH step 1: bounds and set-up, one dispatch.
// Every work group reduces LGH_GROUP * LGH_BOUNDS_ITEMS lights (strided, so loads coalesce) to one
// LghBoundsPartial: the bounds and largest intensity component of the contributing lights (valid,
// luminance > 0) and the counts of contributing and invalid lights - shared atomics on
// order-preserving integer keys within the group, no global float atomics, no initialisation
// pass. The last group to finish (lghFinishLastGroup) reduces the partials and prepares the rest
// of the build on the GPU, so the CPU never waits:
//  - origin = min corner of the contributing lights' bounds; top cell = the longest edge (at least
//    max(1e-6, 1e-4 * max |coordinate|), so a single point or a plane still has a grid);
//  - the fixed-point scale for the portable atomics;
//  - fitLevels: the most levels whose dense grids (all levels) fit the vertex budget;
//  - explicit levels: the level table and every later dispatch's arguments (lghConfigure);
//    auto levels: the layout of the occupancy bitmaps of every candidate L <= fitLevels
//    (lgh_occupancy.comp then chooses L and configures).
// Invalid lights (NaN/inf/out of range) or no contributing light give an empty hierarchy.
#define LGH_BUILD_INTERNALS
#define LGH_COHERENT
#include "include/lgh_types.glsl"

layout(local_size_x = LGH_GROUP) in;

uniform uint u_count;            // lights in the input buffer
uniform uint u_groups;           // groups with lights (the 2D dispatch may round up)
uniform uint u_requestedLevels;  // 0: auto
uniform uint u_budget;           // dense vertices (all levels, block aligned) the buffers hold
uniform uint u_flags;            // LGH_FLAG_* of this build
#define u_lightCount u_count

LghBoundsPartial boundsOfMyLights() {
  LghBoundsPartial mine = LghBoundsPartial(vec4(vec3(3.0e38), 0.0), vec4(-3.0e38), uvec4(0u));
  const uint first = lghGroupIndex() * LGH_GROUP * LGH_BOUNDS_ITEMS + gl_LocalInvocationID.x;
  for (uint k = 0u; k < LGH_BOUNDS_ITEMS; ++k) {
    uint i = first + k * LGH_GROUP;
    if (i >= u_count) break;
    PointLight light = lights[i];
    vec3 p = light.positionPad.xyz;
    vec3 c = light.intensityPad.rgb;
    if (!lghValidLight(p, c)) {
      mine.counts.y += 1u;
    } else if (luminance(c) > 0.0) {
      mine.minMaxC = vec4(min(mine.minMaxC.xyz, p), max(mine.minMaxC.w, max(c.r, max(c.g, c.b))));
      mine.maxPad.xyz = max(mine.maxPad.xyz, p);
      mine.counts.x += 1u;
    }
  }
  return mine;
}

// Folds the bounds partials into one (shared atomics, see lghBoundsAdd).
LghBoundsPartial reducePartials() {
  lghBoundsBegin();
  LghBoundsPartial mine = LghBoundsPartial(vec4(vec3(3.0e38), 0.0), vec4(-3.0e38), uvec4(0u));
  for (uint i = gl_LocalInvocationID.x; i < u_groups; i += LGH_GROUP) {
    LghBoundsPartial p = partials[i];
    if (p.counts.x > 0u) {
      mine.minMaxC = vec4(min(mine.minMaxC.xyz, p.minMaxC.xyz), max(mine.minMaxC.w, p.minMaxC.w));
      mine.maxPad.xyz = max(mine.maxPad.xyz, p.maxPad.xyz);
    }
    mine.counts += p.counts;
  }
  lghBoundsAdd(mine);
  barrier();
  return lghBoundsResult();
}

void writeHeader(uvec2 counts, float maxC) {
  lgh.totalLights = 0u;
  lgh.inputCount = u_lightCount;
  lgh.contributingCount = counts.x;
  lgh.invalidCount = counts.y;
  lgh.requestedLevels = u_requestedLevels;
  lgh.fitLevels = 0u;
  lgh.overflow = 0u;
  lgh.maxIntensity = maxC;
  lgh.flags = u_flags;
  for (uint i = 0u; i < u_levelLimit; ++i) lgh.candidateS1[i] = 0u;
  for (uint i = 0u; i < LGH_DISPATCH_SLOTS; ++i) st.dispatchArgs[i] = uvec4(0u, 1u, 1u, 0u);
  st.lightCount = u_lightCount;
  st.fineLevel = 0u;
  st.bigSteps = 0u;
  st.tailFrom = 0u;
}

// Power-of-two scale with sum(|values|) * scale <= 2^62 for every accumulated quantity: each is
// at most 2 * (contributing lights) * (largest component).
void setFixedScale(uint contributing, float maxC) {
  float e = 61.0 - ceil(log2(float(max(contributing, 1u))) + log2(max(maxC, 1.0e-30)));
  e = clamp(e, -120.0, 120.0);
  lgh.fixedScale = exp2(e);
  lgh.invFixedScale = exp2(-e);
}

// The most levels whose dense grids (every level, block aligned) fit u_budget; at least 1.
uint fitLevels() {
  uint total = 0u;
  uint fit = 1u;
  for (uint L = 1u; L <= u_levelLimit; ++L) {
    uint n = lghVertexCount(lghGridDims(L - 1u));
    if (n == 0xffffffffu) break;
    total += lghAlignBlock(n);
    if (total > u_budget) break;
    fit = L;
  }
  return fit;
}

// Auto levels: the occupancy bitmaps of S1 for every candidate L <= fit (one bit per vertex,
// 8 words per 256 vertices) and the pyramid dispatches; the candidates from tailFrom down are
// left to the tail (see lgh_occupancy.comp).
void layoutCandidates(uint fit) {
  uint words = 0u;
  for (uint L = 1u; L <= fit; ++L) {
    uvec3 dims = lghGridDims(L - 1u);
    uint n = dims.x * dims.y * dims.z;
    st.candDims[L - 1u] = uvec4(dims, n);
    st.candBitmap[L - 1u] = uvec4(words, lghCeilDiv(n, LGH_GROUP) * 8u, 0u, 0u);
    words += lghCeilDiv(n, LGH_GROUP) * 8u;
  }
  uint bigSteps = 0u;
  for (uint L = fit - 1u; L >= 1u && bigSteps < LGH_PYRAMID_STEPS; --L) {
    if (st.candDims[L - 1u].w <= LGH_TAIL_VERTICES) break;
    st.dispatchArgs[LGH_SLOT_PYRAMID + bigSteps] = lghDispatch(lghCeilDiv(st.candDims[L - 1u].w, LGH_GROUP));
    ++bigSteps;
  }
  st.fineLevel = fit;
  st.bigSteps = bigSteps;
  st.tailFrom = fit - 1u - bigSteps;
}

void setup() {
  const LghBoundsPartial bounds = reducePartials();
  if (gl_LocalInvocationID.x != 0u) return;
  const vec4 lo = bounds.minMaxC;
  const vec3 hi = bounds.maxPad.xyz;
  const uvec2 counts = bounds.counts.xy;
  writeHeader(counts, lo.w);
  if (counts.y > 0u || counts.x == 0u) {
    lgh.originH1 = vec4(0.0);
    lgh.boundsMaxTop = vec4(0.0);
    st.extentInvTop = vec4(0.0);
    lghConfigure(0u);
    return;
  }
  precise vec3 extent = hi - lo.xyz;
  float maxAbs = max(max(abs(lo.x), abs(lo.y)), max(max(abs(lo.z), abs(hi.x)), max(abs(hi.y), abs(hi.z))));
  float top = max(max(extent.x, max(extent.y, extent.z)), max(1.0e-6, 1.0e-4 * maxAbs));
  lgh.originH1 = vec4(lo.xyz, 0.0);
  lgh.boundsMaxTop = vec4(hi, top);
  st.extentInvTop = vec4(extent, 1.0 / top);
  setFixedScale(counts.x, lo.w);
  uint fit = fitLevels();
  lgh.fitLevels = fit;
  lghConfigure(0u);
  if (u_requestedLevels > 0u) {
    lghConfigure(min(u_requestedLevels, fit));
  } else {
    layoutCandidates(fit);
  }
}

void main() {
  const bool hasLights = lghGroupIndex() < u_groups;
  lghBoundsBegin();
  if (hasLights) lghBoundsAdd(boundsOfMyLights());
  barrier();
  if (hasLights && gl_LocalInvocationID.x == 0u) partials[lghGroupIndex()] = lghBoundsResult();
#ifndef LGH_BOUNDS_ONLY  // LghBuilder::validate() only reads the partials back
  if (lghFinishLastGroup(0u)) setup();
#endif
}
