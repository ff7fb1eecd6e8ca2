#include "gi/gi_sources.hpp"

#include <array>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace lgh {
namespace {

double luminance(const glm::vec3& rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

}  // namespace

glm::vec3 lightPower(const LightDesc& light, const Bounds& sceneBounds) {
  // Light paths bounce diffusely: they carry the light's diffuse colour (its colour unless set),
  // as the direct lighting's diffuse lobe does; its ambient and specular colours stay direct.
  const std::array<float, 3> color = light.diffuse.value_or(light.color);
  const glm::vec3 emitted =
      glm::max(glm::vec3(color[0], color[1], color[2]) * light.intensity, glm::vec3(0.0F));
  switch (light.type) {
    case LightType::Point:
      return 4.0F * glm::pi<float>() * emitted;
    case LightType::Spot:
      return 2.0F * glm::pi<float>() * (1.0F - std::cos(light.outerConeAngle)) * emitted;
    case LightType::Directional: {
      if (sceneBounds.empty()) return glm::vec3(0.0F);
      const glm::vec3 size = glm::max(sceneBounds.size(), glm::vec3(1e-6F));
      const glm::vec3 d = glm::abs(
          glm::normalize(glm::vec3(light.direction[0], light.direction[1], light.direction[2])));
      const float projected = d.x * size.y * size.z + d.y * size.x * size.z + d.z * size.x * size.y;
      return projected * emitted;
    }
  }
  return glm::vec3(0.0F);
}

GiSourceTable buildGiSources(const std::vector<LightDesc>& lights,
                             const std::vector<EmissiveTriangle>& triangles,
                             const Bounds& sceneBounds) {
  GiSourceTable table;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    GiSourceGpu source;
    source.info = glm::ivec4(kGiSourceLight, static_cast<int>(i), 0, 0);
    source.power = glm::vec4(lightPower(lights[i], sceneBounds), 0.0F);
    if (luminance(glm::vec3(source.power)) > 0.0) table.sources.push_back(source);
  }
  for (const EmissiveTriangle& triangle : triangles) {
    GiSourceGpu source;
    source.info = glm::ivec4(kGiSourceTriangle, 0, triangle.doubleSided ? 1 : 0, 0);
    source.vertex0 = glm::vec4(triangle.vertex0, triangle.area);
    source.edge1 = glm::vec4(triangle.vertex1 - triangle.vertex0, 0.0F);
    source.edge2 = glm::vec4(triangle.vertex2 - triangle.vertex0, 0.0F);
    source.normal = glm::vec4(triangle.normal, 0.0F);
    source.radiance = glm::vec4(triangle.radiance, 0.0F);
    // A Lambertian emitter: pi L A per side.
    const float sides = triangle.doubleSided ? 2.0F : 1.0F;
    source.power = glm::vec4(glm::pi<float>() * triangle.area * sides * triangle.radiance, 0.0F);
    if (luminance(glm::vec3(source.power)) <= 0.0) continue;
    table.sources.push_back(source);
    table.hasTriangles = true;
  }
  for (const GiSourceGpu& source : table.sources) table.totalPower += luminance(source.power);
  double cumulative = 0.0;
  for (GiSourceGpu& source : table.sources) {
    cumulative += luminance(source.power);
    source.power.w = static_cast<float>(cumulative / table.totalPower);
  }
  if (!table.sources.empty()) table.sources.back().power.w = 1.0F;
  return table;
}

}  // namespace lgh
