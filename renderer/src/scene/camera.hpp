// The camera of a request turned into matrices: look-at, a glTF camera, or auto framing of the
// scene bounds from a direction (thumbnails). Near/far planes default from the scene bounds.
#pragma once

#include <glm/glm.hpp>

#include "lgh/request.hpp"
#include "scene/scene.hpp"

namespace lgh {

struct CameraMatrices {
  glm::mat4 view{1.0F};
  glm::mat4 projection{1.0F};
  glm::vec3 position{0.0F};
  float znear = 0.1F;
  float zfar = 100.0F;
  glm::mat4 viewProjection() const { return projection * view; }
};

// Throws lgh::Error(Invalid) naming /camera/... for a glTF camera index out of range.
CameraMatrices computeCamera(const CameraDesc& desc, const Scene& scene, int width, int height);

}  // namespace lgh
