// One glTF animation sampled at one time: the node transforms and morph weights it sets. The
// renderer draws that pose (scene.animation of the request); without one, the asset's own node
// transforms and weights (the bind pose) are drawn.
#pragma once

#include <map>
#include <optional>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/gltf/accessor_reader.hpp"
#include "scene/gltf/load_context.hpp"
#include "scene/gltf/tinygltf.hpp"

namespace lgh::gltf {

struct NodePose {
  std::optional<glm::vec3> translation;
  std::optional<glm::quat> rotation;
  std::optional<glm::vec3> scale;
  std::vector<float> weights;  // empty: the node's (or mesh's) own
};

using AnimationPose = std::map<int, NodePose>;  // by node index

// Samples animation `index` at `time` seconds (clamped to the animation's time range), with
// glTF's STEP, LINEAR (slerp for rotations) and CUBICSPLINE interpolation. An index the asset lacks
// is lgh::Error(Invalid) naming the count; malformed samplers fail like any accessor.
AnimationPose sampleAnimation(const tinygltf::Model& model, LoadContext& ctx,
                              const AccessorReader& reader, int index, float time);

}  // namespace lgh::gltf
