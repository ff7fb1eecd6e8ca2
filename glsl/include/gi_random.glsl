// Random numbers of the light paths and the path-traced reference: stateless hashes of (seed,
// path, bounce, dimension) with the reservoir's PCG hash (include/reservoir.glsl), so a path's
// numbers do not depend on how many threads ran or in which order.
#ifndef LGH_GI_RANDOM_GLSL
#define LGH_GI_RANDOM_GLSL

#include "include/common.glsl"
#include "include/reservoir.glsl"

uint giPathSeed(uint seed, uint path) {
  return reservoirHash(reservoirHash(seed ^ 0x6a09e667u) + reservoirHash(path));
}

// Uniform in [0, 1): dimension 0..15 of a bounce.
float giRandom(uint pathSeed, uint bounce, uint dimension) {
  return reservoirUnit(reservoirHash(pathSeed + bounce * 16u + dimension));
}

// An orthonormal basis around unit n (Duff et al. 2017).
void giBasis(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Cosine-weighted direction about unit n (pdf cos / pi).
vec3 giCosineDirection(vec3 n, vec2 u) {
  vec3 t, b;
  giBasis(n, t, b);
  float r = sqrt(u.x);
  float phi = 2.0 * PI * u.y;
  return normalize(r * cos(phi) * t + r * sin(phi) * b + sqrt(max(0.0, 1.0 - u.x)) * n);
}

// Uniform direction on the sphere.
vec3 giSphereDirection(vec2 u) {
  float z = 1.0 - 2.0 * u.x;
  float r = sqrt(max(0.0, 1.0 - z * z));
  float phi = 2.0 * PI * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

// Uniform direction in the cone of half-angle acos(cosMax) about unit axis.
vec3 giConeDirection(vec3 axis, float cosMax, vec2 u) {
  vec3 t, b;
  giBasis(axis, t, b);
  float cosTheta = 1.0 - u.x * (1.0 - cosMax);
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * PI * u.y;
  return normalize(cosTheta * axis + sinTheta * (cos(phi) * t + sin(phi) * b));
}

// Uniform barycentrics (of vertices 1 and 2) on a triangle.
vec2 giTriangleBarycentrics(vec2 u) {
  float s = sqrt(u.x);
  return vec2(s * (1.0 - u.y), s * u.y);
}

#endif
