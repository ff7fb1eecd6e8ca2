#include "scene/gltf/animation_pose.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

namespace lgh::gltf {
namespace {

struct Keyframes {
  std::vector<float> times;
  std::vector<float> values;  // per key: components (x3 for CUBICSPLINE: in-tangent, value, out)
  std::size_t components = 0;
  bool cubic = false;
  bool step = false;
};

// Where `time` falls: keys k and k + 1 and the fraction between them.
struct Bracket {
  std::size_t key = 0;
  std::size_t next = 0;
  float fraction = 0.0F;
  float span = 0.0F;  // seconds between the two keys
};

Bracket bracket(const std::vector<float>& times, float time) {
  Bracket b;
  if (times.size() < 2 || time <= times.front()) return b;
  if (time >= times.back()) {
    b.key = b.next = times.size() - 1;
    return b;
  }
  const auto it = std::upper_bound(times.begin(), times.end(), time);
  b.next = static_cast<std::size_t>(it - times.begin());
  b.key = b.next - 1;
  b.span = times[b.next] - times[b.key];
  b.fraction = b.span > 0.0F ? (time - times[b.key]) / b.span : 0.0F;
  return b;
}

// Component c of key k: for CUBICSPLINE the value (the middle of in-tangent, value, out-tangent).
float keyValue(const Keyframes& frames, std::size_t key, std::size_t c, std::size_t part = 1) {
  const std::size_t stride = frames.components * (frames.cubic ? 3 : 1);
  return frames.values[key * stride + (frames.cubic ? part * frames.components : 0) + c];
}

std::vector<float> sample(const Keyframes& frames, float time, bool rotation) {
  const Bracket b = bracket(frames.times, time);
  std::vector<float> out(frames.components);
  for (std::size_t c = 0; c < frames.components; ++c) {
    const float a = keyValue(frames, b.key, c);
    const float z = keyValue(frames, b.next, c);
    if (frames.step || b.key == b.next) {
      out[c] = a;
    } else if (frames.cubic) {
      // Hermite spline: glTF's CUBICSPLINE, tangents scaled by the key interval.
      const float t = b.fraction;
      const float t2 = t * t;
      const float t3 = t2 * t;
      const float outTangent = keyValue(frames, b.key, c, 2) * b.span;
      const float inTangent = keyValue(frames, b.next, c, 0) * b.span;
      out[c] = (2 * t3 - 3 * t2 + 1) * a + (t3 - 2 * t2 + t) * outTangent + (-2 * t3 + 3 * t2) * z +
               (t3 - t2) * inTangent;
    } else {
      out[c] = a + (z - a) * b.fraction;
    }
  }
  if (rotation && !frames.cubic && !frames.step && b.key != b.next) {
    const glm::quat qa(keyValue(frames, b.key, 3), keyValue(frames, b.key, 0),
                       keyValue(frames, b.key, 1), keyValue(frames, b.key, 2));
    const glm::quat qz(keyValue(frames, b.next, 3), keyValue(frames, b.next, 0),
                       keyValue(frames, b.next, 1), keyValue(frames, b.next, 2));
    const glm::quat q = glm::slerp(qa, qz, b.fraction);
    out = {q.x, q.y, q.z, q.w};
  }
  return out;
}

Keyframes readKeyframes(const tinygltf::Model& model, LoadContext& ctx,
                        const AccessorReader& reader, const tinygltf::AnimationSampler& sampler,
                        std::size_t components, const std::string& owner) {
  Keyframes frames;
  frames.cubic = sampler.interpolation == "CUBICSPLINE";
  frames.step = sampler.interpolation == "STEP";
  int inputComponents = 0;
  frames.times = reader.readFloats(sampler.input, Semantic::AnimationInput, owner + " input",
                                   &inputComponents);
  int outputComponents = 0;
  frames.values = reader.readFloats(sampler.output, Semantic::AnimationOutput, owner + " output",
                                    &outputComponents);
  frames.components = components;
  const std::size_t expected = frames.times.size() * components * (frames.cubic ? 3 : 1);
  if (frames.times.empty() || frames.values.size() != expected) {
    invalid(ctx, fmt::format("{}: {} keyframe times but {} output values (expected {})", owner,
                             frames.times.size(), frames.values.size(), expected));
  }
  for (float t : frames.times) {
    if (!std::isfinite(t)) invalid(ctx, fmt::format("{}: a keyframe time is not finite", owner));
  }
  (void)model;
  return frames;
}

std::size_t morphTargetCount(const tinygltf::Model& model, const tinygltf::Node& node) {
  if (node.mesh < 0 || static_cast<std::size_t>(node.mesh) >= model.meshes.size()) return 0;
  const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(node.mesh)];
  return mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
}

}  // namespace

AnimationPose sampleAnimation(const tinygltf::Model& model, LoadContext& ctx,
                              const AccessorReader& reader, int index, float time) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.animations.size()) {
    throw Error(
        ErrorCode::Invalid,
        fmt::format("the asset has {} animation(s), no index {}", model.animations.size(), index),
        "/scene/animation/index");
  }
  const tinygltf::Animation& animation = model.animations[static_cast<std::size_t>(index)];
  const std::string name = label("animations", index, animation.name);
  AnimationPose pose;
  for (std::size_t c = 0; c < animation.channels.size(); ++c) {
    const tinygltf::AnimationChannel& channel = animation.channels[c];
    const std::string owner = fmt::format("{} channel {}", name, c);
    if (channel.target_node < 0 ||
        static_cast<std::size_t>(channel.target_node) >= model.nodes.size()) {
      continue;  // no node (e.g. KHR_animation_pointer targets): nothing this renderer poses
    }
    if (channel.sampler < 0 ||
        static_cast<std::size_t>(channel.sampler) >= animation.samplers.size()) {
      invalid(ctx, fmt::format("{}: sampler {} does not exist", owner, channel.sampler));
    }
    const tinygltf::AnimationSampler& sampler =
        animation.samplers[static_cast<std::size_t>(channel.sampler)];
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(channel.target_node)];
    NodePose& target = pose[channel.target_node];
    const std::string& path = channel.target_path;
    if (path == "translation" || path == "scale") {
      const auto v = sample(readKeyframes(model, ctx, reader, sampler, 3, owner), time, false);
      (path == "translation" ? target.translation : target.scale) = glm::vec3(v[0], v[1], v[2]);
    } else if (path == "rotation") {
      const auto v = sample(readKeyframes(model, ctx, reader, sampler, 4, owner), time, true);
      glm::quat q(v[3], v[0], v[1], v[2]);
      const float length = glm::length(q);
      if (std::isfinite(length) && length > 1e-8F) target.rotation = q / length;
    } else if (path == "weights") {
      const std::size_t targets = morphTargetCount(model, node);
      if (targets == 0) continue;
      target.weights =
          sample(readKeyframes(model, ctx, reader, sampler, targets, owner), time, false);
    }
  }
  return pose;
}

}  // namespace lgh::gltf
