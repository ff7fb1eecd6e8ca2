#include "lgh/testing/cpu_lighting.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lgh {
namespace {

constexpr double kPi = std::numbers::pi;
// The dielectric reflectance at normal incidence of the glTF model (an index of refraction of 1.5).
constexpr double kDielectricF0 = 0.04;

// Trowbridge-Reitz / GGX normal distribution, alpha = roughness^2.
double ggx(double nDotH, double alpha) {
  const double a2 = alpha * alpha;
  const double denominator = nDotH * nDotH * (a2 - 1.0) + 1.0;
  return a2 / (kPi * denominator * denominator);
}

// Height-correlated Smith visibility V = G / (4 n.l n.v).
double smithVisibility(double nDotL, double nDotV, double alpha) {
  const double a2 = alpha * alpha;
  const double v = nDotL * std::sqrt(nDotV * nDotV * (1.0 - a2) + a2);
  const double l = nDotV * std::sqrt(nDotL * nDotL * (1.0 - a2) + a2);
  return v + l > 0.0 ? 0.5 / (v + l) : 0.0;
}

}  // namespace

glm::dvec3 cpuBrdfCosine(const CpuSurface& surface, const glm::dvec3& toViewer,
                         const glm::dvec3& toLight) {
  const double nDotL = glm::dot(surface.normal, toLight);
  if (nDotL <= 0.0) return glm::dvec3(0.0);
  // The renderer keeps n.v off zero for surfaces seen edge-on (brdf.glsl): so does the reference.
  const double nDotV = std::max(glm::dot(surface.normal, toViewer), 1e-4);
  const glm::dvec3 h = glm::normalize(toLight + toViewer);
  const double nDotH = std::clamp(glm::dot(surface.normal, h), 0.0, 1.0);
  const double vDotH = std::clamp(glm::dot(toViewer, h), 0.0, 1.0);
  const double alpha = std::max(surface.roughness * surface.roughness, 1e-3);
  const glm::dvec3 f0 = glm::mix(glm::dvec3(kDielectricF0), surface.baseColor, surface.metallic);
  const glm::dvec3 fresnel = f0 + (glm::dvec3(1.0) - f0) * std::pow(1.0 - vDotH, 5.0);
  const glm::dvec3 diffuse =
      (glm::dvec3(1.0) - fresnel) * (1.0 - surface.metallic) * surface.baseColor / kPi;
  const glm::dvec3 specular = fresnel * ggx(nDotH, alpha) * smithVisibility(nDotL, nDotV, alpha);
  return (diffuse + specular) * nDotL;
}

glm::dvec3 cpuPointLightRadiance(const CpuSurface& surface, const glm::dvec3& viewer,
                                 const std::vector<PointLight>& lights, double minDistance2) {
  const glm::dvec3 toViewer = glm::normalize(viewer - surface.position);
  glm::dvec3 radiance(0.0);
  for (const PointLight& light : lights) {
    const glm::dvec3 offset = glm::dvec3(glm::vec3(light.positionPad)) - surface.position;
    const double d2 = glm::dot(offset, offset);
    if (!(d2 > 0.0)) continue;
    const glm::dvec3 toLight = offset / std::sqrt(d2);
    radiance += glm::dvec3(glm::vec3(light.intensityPad)) *
                cpuBrdfCosine(surface, toViewer, toLight) / std::max(d2, minDistance2);
  }
  return radiance;
}

}  // namespace lgh
