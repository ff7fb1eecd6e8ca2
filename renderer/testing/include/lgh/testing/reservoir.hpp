// C++ mirror of glsl/include/reservoir.glsl: streaming weighted reservoir selection of k shadow
// samples (Lin & Yuksel 2019, Sec. 3.3 and Appendix A). Same hash, same float operations, so a
// stream of lights gives the same choices here as on the GPU. See the GLSL file for the estimator.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace lgh::reservoir {

inline constexpr int kMaxSamples = 8;

inline std::uint32_t hash(std::uint32_t v) {
  const std::uint32_t state = v * 747796405U + 2891336453U;
  const std::uint32_t word = ((state >> ((state >> 28U) + 4U)) ^ state) * 277803737U;
  return (word >> 22U) ^ word;
}

inline float unit(std::uint32_t h) { return static_cast<float>(h >> 8U) * (1.0F / 16777216.0F); }

inline std::uint32_t pixelSeed(std::uint32_t frameSeed, std::uint32_t pixelIndex) {
  return hash(frameSeed ^ hash(pixelIndex));
}

inline std::uint32_t lightSeed(std::uint32_t pixel, std::uint32_t lightIndex) {
  return hash(pixel + hash(lightIndex));
}

inline float random(std::uint32_t seed, std::uint32_t sampleIndex, std::uint32_t stream) {
  return unit(hash(seed + sampleIndex * 4U + stream));
}

inline std::uint32_t replaceMask(float f, float runningSum, std::uint32_t seed, int sampleCount) {
  std::uint32_t mask = 0;
  for (int s = 0; s < sampleCount; ++s) {
    if (random(seed, static_cast<std::uint32_t>(s), 0) * runningSum < f) mask |= 1U << s;
  }
  return mask;
}

inline glm::vec3 jitter(const glm::vec3& center, const glm::vec3& variance, std::uint32_t seed,
                        std::uint32_t sampleIndex) {
  const glm::vec3 u(random(seed, sampleIndex, 1), random(seed, sampleIndex, 2),
                    random(seed, sampleIndex, 3));
  return center + (2.0F * u - 1.0F) * glm::sqrt(3.0F * glm::max(variance, glm::vec3(0.0F)));
}

inline float sampleWeight(float runningSum, float f, int sampleCount) {
  return f > 0.0F ? runningSum / (static_cast<float>(sampleCount) * f) : 0.0F;
}

// One pixel's reservoir, streamed light by light as the GPU paths do.
struct Reservoir {
  float runningSum = 0.0F;
  std::array<std::uint32_t, kMaxSamples> light{};
  std::array<float, kMaxSamples> weight{};  // f_i of the chosen light (0: none yet)

  void add(std::uint32_t pixel, std::uint32_t lightIndex, float f, int sampleCount) {
    if (!(f > 0.0F)) return;
    runningSum += f;
    const std::uint32_t mask =
        replaceMask(f, runningSum, lightSeed(pixel, lightIndex), sampleCount);
    for (int s = 0; s < sampleCount; ++s) {
      if ((mask & (1U << s)) == 0) continue;
      light[static_cast<std::size_t>(s)] = lightIndex;
      weight[static_cast<std::size_t>(s)] = f;
    }
  }
};

}  // namespace lgh::reservoir
