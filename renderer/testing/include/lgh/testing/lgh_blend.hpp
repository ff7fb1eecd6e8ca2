// C++ mirror of glsl/include/lgh_blend.glsl: the LGH blending functions, a partition of unity
// over the levels startLevel..topLevel at every distance. See the GLSL file for the formulas.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace lgh {

// r_l = alpha * h_l with h_l = h_1 * 2^(l-1).
inline float lghRadius(int level, float alpha, float h1) {
  return alpha * h1 * std::exp2(static_cast<float>(level - 1));
}

// Weight of a level-`level` grid light at distance d from the shaded point.
inline float lghBlend(float d, int level, int startLevel, int topLevel, float alpha, float h1) {
  if (level < startLevel || level > topLevel) return 0.0F;
  const float r = lghRadius(level, alpha, h1);
  const float rise = level == startLevel ? 1.0F : std::clamp(2.0F * d / r - 1.0F, 0.0F, 1.0F);
  const float fall = level == topLevel ? 1.0F : std::clamp(2.0F - d / r, 0.0F, 1.0F);
  return rise * fall;
}

// Distance beyond which a grid light of `level` contributes nothing: 2 r_l, unbounded at the top.
inline float lghInfluenceRadius(int level, int topLevel, float alpha, float h1) {
  return level == topLevel ? std::numeric_limits<float>::max() : 2.0F * lghRadius(level, alpha, h1);
}

}  // namespace lgh
