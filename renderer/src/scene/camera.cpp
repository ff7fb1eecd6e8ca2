#include "scene/camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "lgh/error.hpp"

namespace lgh {
namespace {

glm::vec3 toVec3(const std::array<float, 3>& v) { return {v[0], v[1], v[2]}; }

float sceneRadius(const Scene& scene) {
  return scene.bounds.empty() ? 1.0F : std::max(glm::length(scene.bounds.size()) * 0.5F, 1e-4F);
}

// Near/far that enclose the scene bounds from `eye`, unless the request set them.
void fitDepthRange(const Scene& scene, const glm::vec3& eye, float requestedNear,
                   float requestedFar, CameraMatrices& camera) {
  const float radius = sceneRadius(scene);
  const glm::vec3 center = scene.bounds.empty() ? glm::vec3(0.0F) : scene.bounds.center();
  const float farthest = glm::length(center - eye) + radius;
  camera.zfar = requestedFar > 0.0F ? requestedFar : farthest * 1.05F;
  camera.znear = requestedNear > 0.0F ? requestedNear : std::max(camera.zfar * 1e-4F, 1e-4F);
}

glm::vec3 safeUp(const glm::vec3& forward, const glm::vec3& up) {
  if (glm::length(glm::cross(forward, up)) > 1e-4F) return up;
  return std::abs(forward.y) < 0.9F ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
}

CameraMatrices lookAtCamera(const CameraDesc& desc, const Scene& scene, float aspect) {
  CameraMatrices camera;
  camera.position = toVec3(desc.position);
  const glm::vec3 target = toVec3(desc.target);
  const glm::vec3 forward = glm::normalize(target - camera.position);
  camera.view = glm::lookAt(camera.position, target, safeUp(forward, toVec3(desc.up)));
  fitDepthRange(scene, camera.position, desc.znear, desc.zfar, camera);
  camera.projection =
      glm::perspective(glm::radians(desc.yfovDegrees), aspect, camera.znear, camera.zfar);
  return camera;
}

CameraMatrices autoCamera(const CameraDesc& desc, const Scene& scene, float aspect) {
  const float radius = sceneRadius(scene) * desc.margin;
  const glm::vec3 center = scene.bounds.empty() ? glm::vec3(0.0F) : scene.bounds.center();
  const float yfov = glm::radians(desc.yfovDegrees);
  // Fit the bounding sphere in the narrower of the two fields of view.
  const float xfov = 2.0F * std::atan(std::tan(yfov * 0.5F) * aspect);
  const float halfFov = 0.5F * std::min(yfov, xfov);
  const float distance = radius / std::sin(halfFov);
  const glm::vec3 direction = glm::normalize(toVec3(desc.viewDirection));
  CameraMatrices camera;
  camera.position = center + direction * distance;
  camera.view = glm::lookAt(camera.position, center, safeUp(-direction, toVec3(desc.up)));
  camera.zfar = desc.zfar > 0.0F ? desc.zfar : distance + radius * 1.5F;
  camera.znear =
      desc.znear > 0.0F ? desc.znear : std::max(distance - radius * 1.5F, camera.zfar * 1e-4F);
  camera.projection = glm::perspective(yfov, aspect, camera.znear, camera.zfar);
  return camera;
}

CameraMatrices gltfCamera(const CameraDesc& desc, const Scene& scene, float aspect) {
  if (desc.gltfCameraIndex < 0 ||
      static_cast<size_t>(desc.gltfCameraIndex) >= scene.cameras.size()) {
    throw Error(ErrorCode::Invalid,
                "the asset has " + std::to_string(scene.cameras.size()) + " camera(s), no index " +
                    std::to_string(desc.gltfCameraIndex),
                "/camera/index");
  }
  const SceneCamera& source = scene.cameras[static_cast<size_t>(desc.gltfCameraIndex)];
  CameraMatrices camera;
  camera.position = glm::vec3(source.world[3]);
  camera.view = glm::inverse(source.world);
  fitDepthRange(scene, camera.position, source.znear, source.zfar, camera);
  if (source.perspective) {
    camera.projection = glm::perspective(source.yfov, aspect, camera.znear, camera.zfar);
  } else {
    const float ymag = source.ymag;
    const float xmag = ymag * aspect;
    camera.projection = glm::ortho(-xmag, xmag, -ymag, ymag, camera.znear, camera.zfar);
  }
  return camera;
}

}  // namespace

CameraMatrices computeCamera(const CameraDesc& desc, const Scene& scene, int width, int height) {
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  switch (desc.kind) {
    case CameraDesc::Kind::LookAt:
      return lookAtCamera(desc, scene, aspect);
    case CameraDesc::Kind::GltfCamera:
      return gltfCamera(desc, scene, aspect);
    case CameraDesc::Kind::Auto:
      return autoCamera(desc, scene, aspect);
    case CameraDesc::Kind::Default:
      return scene.cameras.empty() ? autoCamera(desc, scene, aspect)
                                   : gltfCamera(desc, scene, aspect);
  }
  return autoCamera(desc, scene, aspect);
}

}  // namespace lgh
