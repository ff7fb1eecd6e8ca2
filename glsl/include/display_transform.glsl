// The display transform of a PNG: exposure, tone map and sRGB encoding of linear light to the
// 8-bit codes the file stores. The GPU side of lgh::toDisplay8 (renderer/src/image/
// image_common.cpp), which it follows step for step: the same clamps, the same curves, and the
// sRGB code found by counting the same rounding thresholds (uploaded from the CPU's table), so a
// channel can differ only where float arithmetic puts a value on the other side of one threshold:
// one step at most (tests/integration/test_display_transform.cpp).
#ifndef LGH_DISPLAY_TRANSFORM_GLSL
#define LGH_DISPLAY_TRANSFORM_GLSL

#define LGH_TONE_MAP_NONE 0
#define LGH_TONE_MAP_REINHARD 1
#define LGH_TONE_MAP_ACES 2

// threshold[k]: the smallest linear value whose code is k + 1 (image_common.hpp, srgbThresholds).
uniform float uSrgbThresholds[255];

// Larger linear values all display as white; the clamp keeps Reinhard and ACES away from inf/inf.
const float kLghMaxLinear = 1.0e6;

float lghToneMap(float x, int mode) {
  if (mode == LGH_TONE_MAP_REINHARD) return x / (1.0 + x);
  // Narkowicz 2015, a fit of the ACES RRT + ODT for sRGB.
  if (mode == LGH_TONE_MAP_ACES) return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
  return x;
}

// The number of thresholds at or below `value` (in [0, 1]). The sRGB curve in float arithmetic
// guesses the code to within one; the thresholds then decide, so the guess's rounding never shows.
// The two steps cost two table reads where a binary search over the 255 took eight, each a
// gather with its own branch on a SIMD CPU rasteriser (llvmpipe): see docs/BENCHMARKS.md.
uint lghSrgbCode(float value) {
  float encoded = value <= 0.0031308 ? value * 12.92 : 1.055 * pow(value, 1.0 / 2.4) - 0.055;
  int code = clamp(int(encoded * 255.0 + 0.5), 0, 255);
  if (value < uSrgbThresholds[max(code - 1, 0)] && code > 0) --code;
  if (value >= uSrgbThresholds[min(code, 254)] && code < 255) ++code;
  return uint(code);
}

uint lghDisplayChannel(float linear, int toneMap, float exposure) {
  float value = linear * exposure;
  // NaN and negative values display as black.
  value = value > 0.0 ? min(value, kLghMaxLinear) : 0.0;
  return lghSrgbCode(clamp(lghToneMap(value, toneMap), 0.0, 1.0));
}

// Alpha stays linear: rounded to nearest, halves up, as std::lround does for non-negative values.
// The fraction is compared rather than 0.5 added: the sum would round up values just below a half.
uint lghAlpha8(float alpha) {
  float clamped = alpha > 0.0 ? min(alpha, 1.0) : 0.0;
  precise float scaled = clamped * 255.0;
  float whole = floor(scaled);
  return uint(whole) + (scaled - whole >= 0.5 ? 1u : 0u);
}

#endif
