// Analytic lights packed for the GPU (std430, mirrored by `struct Light` in
// glsl/include/lights.glsl).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "gl/gl_objects.hpp"
#include "lgh/request.hpp"

namespace lgh {

struct GpuLight {
  glm::vec4 positionType;
  glm::vec4 directionRange;
  glm::vec4 ambient;   // rgb x intensity
  glm::vec4 diffuse;   // rgb x intensity
  glm::vec4 specular;  // rgb x intensity
  glm::vec4 attenuation;
  glm::vec4 cone;
};
static_assert(sizeof(GpuLight) == 112, "GpuLight must match the std430 layout of Light");

GpuLight packLight(const LightDesc& light);

// Uploads the lights into `buffer` (grown as needed).
void uploadLights(const std::vector<LightDesc>& lights, gl::SizedBuffer& buffer);

}  // namespace lgh
