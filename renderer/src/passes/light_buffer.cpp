#include "passes/light_buffer.hpp"

#include <cmath>

namespace lgh {

GpuLight packLight(const LightDesc& light) {
  auto v3 = [](const std::array<float, 3>& a) { return glm::vec3(a[0], a[1], a[2]); };
  glm::vec3 direction = v3(light.direction);
  direction = glm::length(direction) > 0.0F ? glm::normalize(direction) : glm::vec3(0, -1, 0);
  GpuLight packed{};
  packed.positionType = glm::vec4(v3(light.position), static_cast<float>(light.type));
  packed.directionRange = glm::vec4(direction, light.range);
  // The lecture's per-light colours; diffuse and specular are the light's colour unless set.
  const float intensity = light.intensity;
  packed.ambient = glm::vec4(v3(light.ambient) * intensity, 0.0F);
  packed.diffuse = glm::vec4(v3(light.diffuse.value_or(light.color)) * intensity, 0.0F);
  packed.specular = glm::vec4(v3(light.specular.value_or(light.color)) * intensity, 0.0F);
  packed.attenuation = glm::vec4(v3(light.attenuation), light.spotExponent);
  // cone.z: the size shadow rays see (glsl/shadow_ray_setup.comp).
  const float shadowSize =
      light.type == LightType::Directional ? light.angularRadius : light.radius;
  packed.cone =
      glm::vec4(std::cos(light.innerConeAngle), std::cos(light.outerConeAngle), shadowSize, 0);
  return packed;
}

void uploadLights(const std::vector<LightDesc>& lights, gl::SizedBuffer& buffer) {
  std::vector<GpuLight> packed;
  packed.reserve(lights.size());
  for (const LightDesc& light : lights) packed.push_back(packLight(light));
  const auto bytes = static_cast<GLsizeiptr>(packed.size() * sizeof(GpuLight));
  buffer.reserve(std::max<GLsizeiptr>(bytes, sizeof(GpuLight)));
  if (bytes > 0) glNamedBufferSubData(buffer.id(), 0, bytes, packed.data());
}

}  // namespace lgh
