#include "lgh/testing/light_sets.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace lgh {
namespace {

class Random {
 public:
  explicit Random(std::uint32_t seed) : rng_(seed) {}
  // [0, 1) from 24 bits: identical on every standard library.
  float uniform() { return static_cast<float>(rng_() >> 8) * (1.0F / 16777216.0F); }
  glm::vec3 uniform3() { return {uniform(), uniform(), uniform()}; }
  float gaussian() {  // Box-Muller
    const float u1 = std::max(uniform(), 1.0e-7F);
    return std::sqrt(-2.0F * std::log(u1)) * std::cos(6.2831853F * uniform());
  }

 private:
  std::mt19937 rng_;
};

PointLight makeLight(const glm::vec3& position, Random& random, float scale) {
  PointLight light;
  light.positionPad = glm::vec4(position, 0.0F);
  light.intensityPad = glm::vec4((glm::vec3(0.2F) + random.uniform3()) * scale, 0.0F);
  return light;
}

float perLight(float flux, int count) {
  return count > 0 ? flux / (0.7F * static_cast<float>(count)) : 0.0F;
}

}  // namespace

std::vector<PointLight> uniformLights(int count, glm::vec3 lo, glm::vec3 hi, std::uint32_t seed,
                                      float flux) {
  Random random(seed);
  std::vector<PointLight> lights;
  lights.reserve(lights.size() + static_cast<std::size_t>(std::max(count, 0)));
  for (int i = 0; i < count; ++i) {
    lights.push_back(makeLight(lo + (hi - lo) * random.uniform3(), random, perLight(flux, count)));
  }
  return lights;
}

std::vector<PointLight> clusteredLights(int count, int clusters, float sigma, glm::vec3 lo,
                                        glm::vec3 hi, std::uint32_t seed, float flux) {
  Random random(seed);
  std::vector<glm::vec3> centres;
  for (int c = 0; c < std::max(clusters, 1); ++c) {
    centres.push_back(lo + (hi - lo) * random.uniform3());
  }
  std::vector<PointLight> lights;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 offset(random.gaussian(), random.gaussian(), random.gaussian());
    lights.push_back(
        makeLight(centres[static_cast<std::size_t>(i) % centres.size()] + sigma * offset, random,
                  perLight(flux, count)));
  }
  return lights;
}

std::vector<PointLight> planeLights(int count, glm::vec3 origin, glm::vec3 u, glm::vec3 v,
                                    std::uint32_t seed, float flux) {
  Random random(seed);
  std::vector<PointLight> lights;
  for (int i = 0; i < count; ++i) {
    const float a = random.uniform();
    const float b = random.uniform();
    lights.push_back(makeLight(origin + a * u + b * v, random, perLight(flux, count)));
  }
  return lights;
}

std::vector<PointLight> latticeLights(int n, glm::vec3 origin, float spacing, std::uint32_t seed,
                                      float flux) {
  Random random(seed);
  std::vector<PointLight> lights;
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        lights.push_back(
            makeLight(origin + spacing * glm::vec3(i, j, k), random, perLight(flux, n * n * n)));
      }
    }
  }
  return lights;
}

glm::dvec3 totalIntensity(const std::vector<PointLight>& lights) {
  glm::dvec3 total(0.0);
  for (const PointLight& light : lights) total += glm::dvec3(glm::vec3(light.intensityPad));
  return total;
}

}  // namespace lgh
