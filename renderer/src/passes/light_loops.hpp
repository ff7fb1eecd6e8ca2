// Per-pixel passes compiled for the frame's numbers of lights, so that their loops over the lights
// unroll. Why: llvmpipe loads a buffer's value at an address common to all SIMD lanes once only
// outside loops (and outside branches that differ between lanes); inside a loop it loads it once
// per lane, and the lights' fields are most of the direct lighting's loads (docs/BENCHMARKS.md).
// A GPU loads them once either way, so only a CPU rasteriser compiles these variants.
#pragma once

#include <string>

#include "passes/shadow_ray_setup_pass.hpp"

namespace lgh {

// Counts above this keep the loop (and the program for any count).
inline constexpr int kMaxUnrolledLights = 8;
inline constexpr int kMaxUnrolledLightSamples = 4;

// "#define LGH_LIGHT_COUNT n" (glsl/direct_lighting.comp), or nothing above kMaxUnrolledLights.
std::string lightCountDefines(int lightCount);

// "#define LGH_SHADOWED_LIGHTS n" and "#define LGH_LIGHT_SAMPLES m" (glsl/include/ray_batch.glsl),
// or nothing where either is above its maximum.
std::string shadowLayoutDefines(const ShadowRayLayout& layout);

}  // namespace lgh
