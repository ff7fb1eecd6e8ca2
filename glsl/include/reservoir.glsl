// Shadow-sample selection by streaming weighted reservoir sampling (Lin & Yuksel 2019, Sec. 3.3
// and Appendix A), mirrored operation by operation in
// renderer/testing/include/lgh/testing/reservoir.hpp (tests/unit/test_reservoir.cpp checks the
// mirror, tests/integration/test_lgh_lighting.cpp this file on the GPU).
//
// A pixel keeps a running sum F of the weights f_i of the lights streamed so far. Light i, with
// f_i > 0, first adds f_i to F and then replaces each of the k samples independently with
// probability f_i / F. After the last light, sample s holds light i with probability f_i / sum f,
// whatever the order the lights came in (Appendix A). Every random decision comes from a hash of
// (frame seed, pixel, light, sample, stream): no state but F and the k samples, so a fragment
// shader can run it with F and the samples in images/buffers, and the result for a given order
// of lights is the same in every path.
//
// The samples are stored as the light index and its f_i while lights stream in; the final form
// (reservoirFinalSample) is the jittered sample position and the weight F / (k f_i), the
// 1 / (k p_i) of the ratio estimator (Heitz et al. 2018): with binary visibilities V_s the
// shadowed luminance is sum_s f_s V_s F / (k f_s) = F * mean(V_s), so the shadow ratio is the mean
// visibility of the k samples.
#ifndef LGH_RESERVOIR_GLSL
#define LGH_RESERVOIR_GLSL

#define LGH_MAX_SHADOW_SAMPLES 8

// PCG hash (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering").
uint reservoirHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Uniform in [0, 1) from the top 24 bits: exact in float, the same on CPU and GPU.
float reservoirUnit(uint h) { return float(h >> 8u) * (1.0 / 16777216.0); }

uint reservoirPixelSeed(uint frameSeed, uint pixelIndex) {
  return reservoirHash(frameSeed ^ reservoirHash(pixelIndex));
}

// reservoirLightSeed in two steps, for passes that stream one light into many pixels: the light's
// hash is the same for all of them.
uint reservoirLightHash(uint lightIndex) { return reservoirHash(lightIndex); }

uint reservoirLightSeedOfHash(uint pixelSeed, uint lightHash) {
  return reservoirHash(pixelSeed + lightHash);
}

uint reservoirLightSeed(uint pixelSeed, uint lightIndex) {
  return reservoirLightSeedOfHash(pixelSeed, reservoirLightHash(lightIndex));
}

// Stream 0: the replacement decision; streams 1..3: the jitter along x, y, z.
float reservoirRandom(uint lightSeed, uint sampleIndex, uint stream) {
  return reservoirUnit(reservoirHash(lightSeed + sampleIndex * 4u + stream));
}

// The samples (bit s for sample s) that light i takes over, given its weight f > 0 and the
// running sum F that already includes f: each with probability f / F.
uint reservoirReplaceMask(float f, float runningSum, uint lightSeed, int sampleCount) {
  uint mask = 0u;
  for (int s = 0; s < sampleCount; ++s) {
    if (reservoirRandom(lightSeed, uint(s), 0u) * runningSum < f) mask |= 1u << uint(s);
  }
  return mask;
}

// The chosen light's position jittered by its positional variance: a uniform box per axis with
// the same variance (half-width sqrt(3 var)), so shadows of grid lights get soft penumbrae.
vec3 reservoirJitter(vec3 center, vec3 variance, uint lightSeed, uint sampleIndex) {
  vec3 u = vec3(reservoirRandom(lightSeed, sampleIndex, 1u), reservoirRandom(lightSeed, sampleIndex, 2u),
                reservoirRandom(lightSeed, sampleIndex, 3u));
  return center + (2.0 * u - 1.0) * sqrt(3.0 * max(variance, vec3(0.0)));
}

// The in-flight form of a sample slot: (light index bits, f_i, 0, 0); f_i = 0: no light yet.
vec4 reservoirPendingSample(uint lightIndex, float f) {
  return vec4(uintBitsToFloat(lightIndex), f, 0.0, 0.0);
}

float reservoirSampleWeight(float runningSum, float f, int sampleCount) {
  return f > 0.0 ? runningSum / (float(sampleCount) * f) : 0.0;
}

#endif
