// Morph targets and skins applied to one primitive on the CPU (PrimitiveConverter::
// applyMorphTargets / applySkin): the renderer draws a pose, not an animation, so the deformed
// vertices are computed once at load time and every pass (G-buffer, VPL placement, ray tracing,
// camera framing) sees the same geometry.
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/matrix_inverse.hpp>

#include "scene/gltf/primitive_converter.hpp"

namespace lgh::gltf {

void PrimitiveConverter::applyMorphTargets(const tinygltf::Primitive& source,
                                           const std::string& owner,
                                           const std::vector<float>& weights, bool hasNormals,
                                           bool hasTangents, Primitive& primitive) const {
  const std::size_t count = primitive.vertices.size();
  const std::size_t targets = std::min(weights.size(), source.targets.size());
  for (std::size_t t = 0; t < targets; ++t) {
    const float weight = weights[t];
    if (weight == 0.0F || !std::isfinite(weight)) continue;
    auto delta = [&](const char* name) -> std::vector<float> {
      const auto it = source.targets[t].find(name);
      if (it == source.targets[t].end()) return {};
      const std::string what = fmt::format("{} morph target {} {}", owner, t, name);
      int components = 0;
      std::vector<float> values =
          reader_.readFloats(it->second, Semantic::MorphDelta, what, &components);
      if (values.size() != count * 3) {
        invalid(ctx_, fmt::format("{}: accessor {} has {} elements but POSITION has {}", what,
                                  it->second, values.size() / 3, count));
      }
      return values;
    };
    const std::vector<float> positions = delta("POSITION");
    const std::vector<float> normals = hasNormals ? delta("NORMAL") : std::vector<float>{};
    const std::vector<float> tangents = hasTangents ? delta("TANGENT") : std::vector<float>{};
    for (std::size_t i = 0; i < count; ++i) {
      Vertex& v = primitive.vertices[i];
      if (!positions.empty()) {
        v.position +=
            weight * glm::vec3(positions[i * 3], positions[i * 3 + 1], positions[i * 3 + 2]);
      }
      if (!normals.empty()) {
        v.normal += weight * glm::vec3(normals[i * 3], normals[i * 3 + 1], normals[i * 3 + 2]);
      }
      if (!tangents.empty()) {
        v.tangent += glm::vec4(
            weight * glm::vec3(tangents[i * 3], tangents[i * 3 + 1], tangents[i * 3 + 2]), 0.0F);
      }
    }
  }
  for (std::size_t i = 0; i < count; ++i) {
    const glm::vec3& p = primitive.vertices[i].position;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      invalid(ctx_,
              fmt::format("{}: morph targets move vertex {} to a non-finite position", owner, i));
    }
  }
}

void PrimitiveConverter::applySkin(const tinygltf::Primitive& source, const std::string& owner,
                                   const std::vector<glm::mat4>& jointMatrices,
                                   Primitive& primitive) const {
  const std::size_t count = primitive.vertices.size();
  std::vector<glm::mat4> skinMatrices(count, glm::mat4(0.0F));
  std::vector<float> totalWeight(count, 0.0F);
  for (int set = 0;; ++set) {
    const std::string jointsName = fmt::format("JOINTS_{}", set);
    const std::string weightsName = fmt::format("WEIGHTS_{}", set);
    const int jointsAccessor = attributeAccessor(source, jointsName.c_str());
    const int weightsAccessor = attributeAccessor(source, weightsName.c_str());
    if (jointsAccessor < 0 || weightsAccessor < 0) break;
    int components = 0;
    const std::vector<float> joints =
        readAttribute(source, jointsName.c_str(), Semantic::Joints, owner, count, &components);
    const std::vector<float> weights =
        readAttribute(source, weightsName.c_str(), Semantic::Weights, owner, count, &components);
    for (std::size_t i = 0; i < count; ++i) {
      for (std::size_t k = 0; k < 4; ++k) {
        const float weight = weights[i * 4 + k];
        if (weight == 0.0F || !std::isfinite(weight)) continue;
        const auto joint = static_cast<std::size_t>(joints[i * 4 + k]);
        if (joint >= jointMatrices.size()) {
          invalid(ctx_, fmt::format("{}: {} names joint {} at vertex {}, but the skin has {}",
                                    owner, jointsName, joint, i, jointMatrices.size()));
        }
        skinMatrices[i] += weight * jointMatrices[joint];
        totalWeight[i] += weight;
      }
    }
  }
  std::size_t unweighted = 0;
  for (std::size_t i = 0; i < count; ++i) {
    Vertex& v = primitive.vertices[i];
    glm::mat4 skin = skinMatrices[i];
    if (!(totalWeight[i] > 1e-6F)) {
      ++unweighted;
      skin = jointMatrices.empty() ? glm::mat4(1.0F) : jointMatrices[0];
    } else {
      skin /= totalWeight[i];  // weights should sum to 1; renormalise those that do not
    }
    v.position = glm::vec3(skin * glm::vec4(v.position, 1.0F));
    const glm::mat3 linear(skin);
    v.normal = glm::inverseTranspose(linear) * v.normal;
    v.tangent = glm::vec4(linear * glm::vec3(v.tangent), v.tangent.w);
    if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) ||
        !std::isfinite(v.position.z)) {
      invalid(ctx_, fmt::format("{}: the skin moves vertex {} to a non-finite position", owner, i));
    }
  }
  if (unweighted > 0) {
    ctx_.warnings.push_back(
        fmt::format("{}: {} skinned vertices have no joint weight; bound to the skin's first joint",
                    owner, unweighted));
  }
}

}  // namespace lgh::gltf
