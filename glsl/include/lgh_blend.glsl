// LGH blending functions (Yuksel & Yuksel 2017; Lin & Yuksel 2019, Fig. 2), mirrored in
// renderer/testing/include/lgh/testing/lgh_blend.hpp (tests/unit/test_lgh_blend.cpp checks the
// partition of unity; tests/integration/test_lgh_build.cpp checks this file against the mirror).
//
// d: distance from the shaded point to the grid light; r_l = alpha * h_l = alpha * h_1 * 2^(l-1).
// Lighting uses levels startLevel..topLevel. With rise_l(d) = clamp(d / r_(l-1) - 1, 0, 1)
// (0 up to r_(l-1), 1 from r_l = 2 r_(l-1) on) and fall_l(d) = clamp(2 - d / r_l, 0, 1) (1 up to
// r_l, 0 from 2 r_l on):
//   lowest level (l == startLevel):  B = fall_l          1 for d <= r, linear to 0 at 2r
//   middle level:                    B = rise_l * fall_l 0 up to r_(l-1), up to 1 at r_l, 0 at 2r_l
//   top level (l == topLevel):       B = rise_l          0 up to r_(top-1), 1 from r_top on
//   only one level used (start == top): B = 1.
// Where level l falls (r_l..2r_l) level l+1 rises by the same amount, so the levels in use sum
// to 1 at every d (a partition of unity); a grid light has no influence beyond 2 r_l (not top) and
// none within r_(l-1) (not lowest).
#ifndef LGH_BLEND_GLSL
#define LGH_BLEND_GLSL

float lghRadius(int level, float alpha, float h1) { return alpha * h1 * exp2(float(level - 1)); }

// Level l's blending as a function of d alone: its radius and whether it is the lowest or the top
// level in use. A pass that streams one level's lights sets it up once per level instead of once
// per light and pixel; lghBlend() is the same arithmetic.
struct LghLevelBlend {
  float radius;
  bool lowest;
  bool top;
};

LghLevelBlend lghLevelBlend(int level, int startLevel, int topLevel, float alpha, float h1) {
  return LghLevelBlend(lghRadius(level, alpha, h1), level == startLevel, level == topLevel);
}

float lghBlendAt(LghLevelBlend level, float d) {
  float rise = level.lowest ? 1.0 : clamp(2.0 * d / level.radius - 1.0, 0.0, 1.0);
  float fall = level.top ? 1.0 : clamp(2.0 - d / level.radius, 0.0, 1.0);
  return rise * fall;
}

float lghBlend(float d, int level, int startLevel, int topLevel, float alpha, float h1) {
  if (level < startLevel || level > topLevel) return 0.0;
  return lghBlendAt(lghLevelBlend(level, startLevel, topLevel, alpha, h1), d);
}

// Distance beyond which the grid light of `level` contributes nothing (light-volume radius).
float lghInfluenceRadius(int level, int topLevel, float alpha, float h1) {
  return level == topLevel ? 3.0e38 : 2.0 * lghRadius(level, alpha, h1);
}

#endif
