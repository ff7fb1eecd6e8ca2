#include "scene/gltf/scene_builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "scene/gltf/accessor_reader.hpp"
#include "scene/gltf/animation_pose.hpp"
#include "scene/gltf/material_converter.hpp"
#include "scene/gltf/primitive_converter.hpp"
#include "scene/tangents.hpp"

namespace lgh::gltf {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxNodeDepth = 64;
// Node visits (instances of nodes) before a hierarchy counts as a decompression bomb: a DAG that
// shares children doubles per level.
constexpr std::size_t kMaxNodeVisits = 1U << 20;

glm::mat4 nodeMatrix(const tinygltf::Node& node, const NodePose* pose) {
  if (pose != nullptr && (pose->translation || pose->rotation || pose->scale)) {
    // An animated node: its TRS with the animated parts replaced (glTF animates only TRS nodes).
    glm::vec3 t(0.0F);
    glm::quat r(1.0F, 0.0F, 0.0F, 0.0F);
    glm::vec3 sc(1.0F);
    if (node.translation.size() == 3) {
      t = glm::vec3(node.translation[0], node.translation[1], node.translation[2]);
    }
    if (node.rotation.size() == 4) {
      r = glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                    static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
    }
    if (node.scale.size() == 3) sc = glm::vec3(node.scale[0], node.scale[1], node.scale[2]);
    if (pose->translation) t = *pose->translation;
    if (pose->rotation) r = *pose->rotation;
    if (pose->scale) sc = *pose->scale;
    const float length = glm::length(r);
    const glm::mat4 rotation =
        std::isfinite(length) && length > 1e-8F ? glm::mat4_cast(r / length) : glm::mat4(1.0F);
    return glm::translate(glm::mat4(1.0F), t) * rotation * glm::scale(glm::mat4(1.0F), sc);
  }
  if (node.matrix.size() == 16) {
    glm::mat4 matrix(1.0F);
    for (int i = 0; i < 16; ++i) matrix[i / 4][i % 4] = static_cast<float>(node.matrix[i]);
    return matrix;  // column-major, as glTF stores it
  }
  glm::mat4 matrix(1.0F);
  if (node.translation.size() == 3) {
    matrix = glm::translate(
        matrix, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
  }
  if (node.rotation.size() == 4) {
    // glTF stores x, y, z, w; glm::quat takes w first.
    glm::quat rotation(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                       static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
    const float length = glm::length(rotation);
    if (std::isfinite(length) && length > 1e-8F) matrix *= glm::mat4_cast(rotation / length);
  }
  if (node.scale.size() == 3) {
    matrix = glm::scale(matrix, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
  }
  return matrix;
}

using gltf::isFinite;  // the glm::vec4 overload, which the one below would hide

bool isFinite(const glm::mat4& matrix) {
  for (int c = 0; c < 4; ++c) {
    if (!isFinite(matrix[c])) return false;
  }
  return true;
}

std::array<float, 3> toArray(const glm::vec3& v) { return {v.x, v.y, v.z}; }

class SceneBuilder {
 public:
  SceneBuilder(const tinygltf::Model& model, LoadContext& ctx)
      : model_(model),
        ctx_(ctx),
        reader_(model, ctx, usesExtension("KHR_mesh_quantization")),
        primitives_(model, ctx, reader_),
        materials_(model, ctx, scene_),
        meshRemap_(model.meshes.size(), -1),
        onPath_(model.nodes.size(), false) {}

  Scene build() {
    scene_.name = fs::path(ctx_.displayName).stem().string();
    if (scene_.name.empty()) scene_.name = "scene";
    if (ctx_.options.animation) {
      pose_ = sampleAnimation(model_, ctx_, reader_, ctx_.options.animation->index,
                              ctx_.options.animation->time);
    }
    variant_ = chosenVariant();
    for (const auto& [node, referrer] : rootNodes()) visit(node, glm::mat4(1.0F), 0, referrer);
    // A valid asset may draw nothing (a scene without nodes): an empty image, not an error, so
    // that a batch of thumbnails does not fail on it.
    const bool empty = scene_.triangleCount() == 0 && scene_.lineAndPointPrimitiveCount() == 0;
    if (empty) ctx_.warnings.push_back("the asset's scene has no geometry: nothing is drawn");
    for (std::size_t i = 0; i < model_.materials.size(); ++i) {
      scene_.materials.push_back(materials_.convert(static_cast<int>(i)));
    }
    scene_.textures = materials_.allTextures();
    materials_.warnAboutUnusedFailures();
    scene_.computeBounds();
    if (!empty) checkBounds();
    scene_.warnings = std::move(ctx_.warnings);
    return std::move(scene_);
  }

 private:
  bool usesExtension(const std::string& name) const {
    const auto& used = model_.extensionsUsed;
    return std::find(used.begin(), used.end(), name) != used.end();
  }

  // The default scene's roots (scene 0 when none is named), with the JSON pointer that names
  // each; with no scenes at all, every node that is nobody's child.
  std::vector<std::pair<int, std::string>> rootNodes() const {
    std::vector<std::pair<int, std::string>> roots;
    if (!model_.scenes.empty()) {
      const int chosen = model_.defaultScene >= 0 && static_cast<std::size_t>(model_.defaultScene) <
                                                         model_.scenes.size()
                             ? model_.defaultScene
                             : 0;
      if (model_.defaultScene >= 0 && chosen != model_.defaultScene) {
        ctx_.warnings.push_back(
            fmt::format("default scene {} does not exist; scene 0 used", model_.defaultScene));
      }
      const std::vector<int>& nodes = model_.scenes[static_cast<std::size_t>(chosen)].nodes;
      for (std::size_t k = 0; k < nodes.size(); ++k) {
        roots.emplace_back(nodes[k], fmt::format("/scenes/{}/nodes/{}", chosen, k));
      }
      return roots;
    }
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes) {
      for (int child : node.children) {
        if (child >= 0 && static_cast<std::size_t>(child) < isChild.size()) {
          isChild[static_cast<std::size_t>(child)] = true;
        }
      }
    }
    for (std::size_t i = 0; i < isChild.size(); ++i) {
      if (!isChild[i]) roots.emplace_back(static_cast<int>(i), fmt::format("/nodes/{}", i));
    }
    return roots;
  }

  void visit(int index, const glm::mat4& parent, int depth, const std::string& referrer) {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size()) {
      invalid(ctx_, fmt::format("{} names node {}, which does not exist", referrer, index));
    }
    const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(index)];
    const std::string where = label("nodes", index, node.name);
    if (onPath_[static_cast<std::size_t>(index)]) {
      invalid(ctx_, fmt::format("the node hierarchy has a cycle: {} is its own ancestor (at {})",
                                where, referrer));
    }
    if (depth >= kMaxNodeDepth) {
      invalid(ctx_, fmt::format("the node hierarchy is deeper than {} levels (at {})",
                                kMaxNodeDepth, where));
    }
    if (++visits_ > kMaxNodeVisits) {
      tooLarge(ctx_, fmt::format("the node hierarchy expands to more than {} node instances",
                                 kMaxNodeVisits));
    }
    const glm::mat4 world = parent * localMatrix(index);
    if (!isFinite(world)) invalid(ctx_, fmt::format("{} has a non-finite transform", where));
    if (node.mesh >= 0) addInstance(index, node.mesh, world, where);
    if (node.camera >= 0) addCamera(node.camera, world, where);
    addLight(node, world, where);
    onPath_[static_cast<std::size_t>(index)] = true;
    for (std::size_t k = 0; k < node.children.size(); ++k) {
      visit(node.children[k], world, depth + 1, fmt::format("/nodes/{}/children/{}", index, k));
    }
    onPath_[static_cast<std::size_t>(index)] = false;
  }

  void addInstance(int nodeIndex, int meshIndex, const glm::mat4& world, const std::string& where) {
    if (static_cast<std::size_t>(meshIndex) >= model_.meshes.size()) {
      invalid(ctx_, fmt::format("{} refers to mesh {}, which does not exist", where, meshIndex));
    }
    const Deformation deformation = deformationOf(nodeIndex, meshIndex, where);
    const int sceneMesh =
        deformation.empty() ? convertedMesh(meshIndex) : deformedMesh(meshIndex, deformation);
    if (sceneMesh < 0) return;
    trianglesDrawn_ += meshTriangles_[static_cast<std::size_t>(sceneMesh)];
    if (trianglesDrawn_ > ctx_.limits.maxTriangles) {
      tooLarge(ctx_, fmt::format("the asset draws more than {} triangles (at {})",
                                 ctx_.limits.maxTriangles, where));
    }
    // A skinned mesh is posed by its joints, in world space: the node's own transform does not
    // apply (glTF: "only the joint transforms are applied to the skinned mesh").
    scene_.instances.push_back(
        {sceneMesh, deformation.jointMatrices.empty() ? world : glm::mat4(1.0F)});
  }

  // glTF node `index`'s local matrix in the chosen pose.
  glm::mat4 localMatrix(int index) const {
    const auto it = pose_.find(index);
    return nodeMatrix(model_.nodes[static_cast<std::size_t>(index)],
                      it == pose_.end() ? nullptr : &it->second);
  }

  // World matrix of any node, through its parents (joints need nodes the traversal has not
  // reached yet). Cycles and depth were checked by the traversal; the depth bound here only
  // keeps a malformed parent chain from recursing forever.
  glm::mat4 worldMatrix(int index, int depth = 0) {
    if (worldCache_.empty()) buildParents();
    auto& cached = worldCache_[static_cast<std::size_t>(index)];
    if (cached) return *cached;
    if (depth > kMaxNodeDepth) {
      invalid(ctx_, fmt::format("the node hierarchy is deeper than {} levels (at node {})",
                                kMaxNodeDepth, index));
    }
    const int parent = parents_[static_cast<std::size_t>(index)];
    const glm::mat4 world =
        (parent >= 0 ? worldMatrix(parent, depth + 1) : glm::mat4(1.0F)) * localMatrix(index);
    worldCache_[static_cast<std::size_t>(index)] = world;
    return world;
  }

  void buildParents() {
    parents_.assign(model_.nodes.size(), -1);
    worldCache_.assign(model_.nodes.size(), std::nullopt);
    for (std::size_t i = 0; i < model_.nodes.size(); ++i) {
      for (int child : model_.nodes[i].children) {
        if (child >= 0 && static_cast<std::size_t>(child) < parents_.size() &&
            parents_[static_cast<std::size_t>(child)] < 0 && static_cast<std::size_t>(child) != i) {
          parents_[static_cast<std::size_t>(child)] = static_cast<int>(i);
        }
      }
    }
  }

  // The morph weights (animated, the node's, or the mesh's) and the skin of a node's mesh.
  Deformation deformationOf(int nodeIndex, int meshIndex, const std::string& where) {
    Deformation deformation;
    const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(nodeIndex)];
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(meshIndex)];
    const auto posed = pose_.find(nodeIndex);
    std::vector<float> weights;
    if (posed != pose_.end() && !posed->second.weights.empty()) {
      weights = posed->second.weights;
    } else {
      const std::vector<double>& stored = !node.weights.empty() ? node.weights : mesh.weights;
      for (double w : stored) weights.push_back(finiteOr(w, 0.0F));
    }
    const bool anyWeight =
        std::any_of(weights.begin(), weights.end(), [](float w) { return w != 0.0F; });
    if (anyWeight) deformation.morphWeights = std::move(weights);
    if (node.skin >= 0) deformation.jointMatrices = jointMatrices(node.skin, where);
    return deformation;
  }

  std::vector<glm::mat4> jointMatrices(int skinIndex, const std::string& where) {
    if (static_cast<std::size_t>(skinIndex) >= model_.skins.size()) {
      invalid(ctx_, fmt::format("{} refers to skin {}, which does not exist", where, skinIndex));
    }
    const tinygltf::Skin& skin = model_.skins[static_cast<std::size_t>(skinIndex)];
    const std::string owner = label("skins", skinIndex, skin.name);
    std::vector<float> inverseBind;
    if (skin.inverseBindMatrices >= 0) {
      int components = 0;
      inverseBind = reader_.readFloats(skin.inverseBindMatrices, Semantic::Matrix,
                                       owner + "/inverseBindMatrices", &components);
      if (inverseBind.size() < skin.joints.size() * 16) {
        invalid(ctx_, fmt::format("{}: {} inverse bind matrices for {} joints", owner,
                                  inverseBind.size() / 16, skin.joints.size()));
      }
    }
    std::vector<glm::mat4> matrices;
    matrices.reserve(skin.joints.size());
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      const int joint = skin.joints[j];
      if (joint < 0 || static_cast<std::size_t>(joint) >= model_.nodes.size()) {
        invalid(ctx_,
                fmt::format("{}: joint {} names node {}, which does not exist", owner, j, joint));
      }
      glm::mat4 ibm(1.0F);
      if (!inverseBind.empty()) ibm = glm::make_mat4(inverseBind.data() + j * 16);
      const glm::mat4 matrix = worldMatrix(joint) * ibm;
      if (!isFinite(matrix)) {
        invalid(ctx_, fmt::format("{}: joint {} has a non-finite matrix", owner, j));
      }
      matrices.push_back(matrix);
    }
    if (matrices.empty()) invalid(ctx_, fmt::format("{} has no joints", owner));
    return matrices;
  }

  // KHR_materials_variants: the index of the variant the request named; -1 for none.
  int chosenVariant() const {
    const std::string& wanted = ctx_.options.materialVariant;
    if (wanted.empty()) return -1;
    std::vector<std::string> names;
    const auto it = model_.extensions.find("KHR_materials_variants");
    if (it != model_.extensions.end() && it->second.Has("variants")) {
      const tinygltf::Value& variants = it->second.Get("variants");
      for (std::size_t v = 0; variants.IsArray() && v < variants.ArrayLen(); ++v) {
        const tinygltf::Value& entry = variants.Get(static_cast<int>(v));
        names.push_back(entry.Has("name") && entry.Get("name").IsString()
                            ? entry.Get("name").Get<std::string>()
                            : std::string());
        if (names.back() == wanted) return static_cast<int>(v);
      }
    }
    throw Error(ErrorCode::Invalid,
                names.empty()
                    ? fmt::format("the asset has no material variants (asked for '{}')", wanted)
                    : fmt::format("the asset has no material variant '{}'; it has: {}", wanted,
                                  fmt::join(names, ", ")),
                "/scene/material_variant");
  }

  // A mesh converted for one node's deformation (never shared with other nodes).
  int deformedMesh(int index, const Deformation& deformation) {
    return appendMesh(index, deformation);
  }

  // The Scene::meshes index of glTF mesh `index`, converting it on first use; -1 when it has no
  // triangles.
  int convertedMesh(int index) {
    int& slot = meshRemap_[static_cast<std::size_t>(index)];
    if (slot != -1) return slot;
    const int converted = appendMesh(index, Deformation{});
    slot = converted < 0 ? -2 : converted;  // -2: converted, nothing to draw
    return converted;
  }

  // Converts glTF mesh `index` into a new Scene::meshes entry; -1 when nothing is drawable.
  int appendMesh(int index, const Deformation& deformation) {
    const tinygltf::Mesh& source = model_.meshes[static_cast<std::size_t>(index)];
    Mesh mesh;
    mesh.name = source.name;
    std::size_t elements = 0;
    for (std::size_t p = 0; p < source.primitives.size(); ++p) {
      auto primitive = primitives_.convert(index, static_cast<int>(p), trianglesDrawn_ + elements,
                                           deformation, variant_);
      if (!primitive) continue;
      const bool triangles = primitive->topology == Topology::Triangles;
      elements += primitive->indices.size() / (triangles ? 3 : 1);
      (triangles ? mesh.primitives : mesh.linesAndPoints).push_back(std::move(*primitive));
    }
    if (mesh.primitives.empty() && mesh.linesAndPoints.empty()) return -1;
    scene_.meshes.push_back(std::move(mesh));
    meshTriangles_.push_back(elements);
    return static_cast<int>(scene_.meshes.size()) - 1;
  }

  void addCamera(int index, const glm::mat4& world, const std::string& where) {
    if (static_cast<std::size_t>(index) >= model_.cameras.size()) {
      invalid(ctx_, fmt::format("{} refers to camera {}, which does not exist", where, index));
    }
    const tinygltf::Camera& source = model_.cameras[static_cast<std::size_t>(index)];
    SceneCamera camera;
    camera.name = source.name;
    camera.world = world;
    if (source.type == "perspective") {
      const auto& p = source.perspective;
      camera.perspective = true;
      camera.yfov = static_cast<float>(p.yfov);
      camera.aspectRatio = static_cast<float>(p.aspectRatio);
      camera.znear = static_cast<float>(p.znear);
      camera.zfar = static_cast<float>(p.zfar);
      const bool valid = camera.yfov > 0.0F && camera.yfov < 3.14F && camera.znear > 0.0F &&
                         camera.aspectRatio >= 0.0F &&
                         (camera.zfar == 0.0F || camera.zfar > camera.znear);
      if (valid) {
        scene_.cameras.push_back(camera);
        return;
      }
    } else if (source.type == "orthographic") {
      const auto& o = source.orthographic;
      camera.perspective = false;
      camera.xmag = static_cast<float>(o.xmag);
      camera.ymag = static_cast<float>(o.ymag);
      camera.znear = static_cast<float>(o.znear);
      camera.zfar = static_cast<float>(o.zfar);
      const bool valid = camera.xmag != 0.0F && camera.ymag != 0.0F && camera.znear >= 0.0F &&
                         camera.zfar > camera.znear && std::isfinite(camera.xmag) &&
                         std::isfinite(camera.ymag) && std::isfinite(camera.zfar);
      if (valid) {
        scene_.cameras.push_back(camera);
        return;
      }
    }
    ctx_.warnings.push_back(fmt::format("{} of {} has an invalid type or projection; skipped",
                                        label("cameras", index, source.name), where));
  }

  void addLight(const tinygltf::Node& node, const glm::mat4& world, const std::string& where) {
    const auto it = node.extensions.find("KHR_lights_punctual");
    if (it == node.extensions.end() || !it->second.Has("light")) return;
    const tinygltf::Value& value = it->second.Get("light");
    const int index = value.IsNumber() ? value.GetNumberAsInt() : -1;
    if (index < 0 || static_cast<std::size_t>(index) >= model_.lights.size()) {
      invalid(ctx_, fmt::format("{} refers to light {}, which does not exist", where, index));
    }
    const tinygltf::Light& source = model_.lights[static_cast<std::size_t>(index)];
    const std::optional<LightType> type = lightType(source.type);
    const glm::vec3 position(world * glm::vec4(0, 0, 0, 1));
    const glm::vec3 direction(world * glm::vec4(0, 0, -1, 0));  // lights shine along local -Z
    if (!type || (*type != LightType::Point && !isUsableDirection(direction))) {
      ctx_.warnings.push_back(
          fmt::format("{} of {} has an unknown type or a degenerate direction; skipped",
                      label("extensions/KHR_lights_punctual/lights", index, source.name), where));
      return;
    }
    LightDesc light;
    light.type = *type;
    light.position = toArray(position);
    if (isUsableDirection(direction)) light.direction = toArray(glm::normalize(direction));
    for (int c = 0; c < 3 && c < static_cast<int>(source.color.size()); ++c) {
      light.color[static_cast<std::size_t>(c)] = std::max(finiteOr(source.color[c], 1.0F), 0.0F);
    }
    light.intensity = std::max(finiteOr(source.intensity, 1.0F), 0.0F);
    light.range = std::max(finiteOr(source.range, 0.0F), 0.0F);
    light.attenuation = {0.0F, 0.0F, 1.0F};  // KHR_lights_punctual: inverse square
    setCone(light, source, where);
    scene_.lights.push_back(light);
  }

  static std::optional<LightType> lightType(const std::string& type) {
    if (type == "directional") return LightType::Directional;
    if (type == "point") return LightType::Point;
    if (type == "spot") return LightType::Spot;
    return std::nullopt;
  }

  // KHR_lights_punctual: 0 <= inner < outer <= pi/2. Out-of-range angles are clamped.
  void setCone(LightDesc& light, const tinygltf::Light& source, const std::string& where) {
    if (light.type != LightType::Spot) return;
    constexpr float kHalfPi = 1.5707964F;
    const float outer = std::clamp(finiteOr(source.spot.outerConeAngle, 0.785398F), 1e-4F, kHalfPi);
    const float inner =
        std::clamp(finiteOr(source.spot.innerConeAngle, 0.0F), 0.0F, outer * 0.999F);
    // Compared in double: the float round trip of a valid angle is not a clamp.
    const bool clamped = !(std::abs(outer - source.spot.outerConeAngle) <= 1e-6) ||
                         !(std::abs(inner - source.spot.innerConeAngle) <= 1e-6);
    if (clamped) {
      ctx_.warnings.push_back(
          fmt::format("spot light of {}: cone angles clamped to {} / {}", where, inner, outer));
    }
    light.innerConeAngle = inner;
    light.outerConeAngle = outer;
  }

  void checkBounds() const {
    const Bounds& b = scene_.bounds;
    const bool finite = std::isfinite(b.min.x) && std::isfinite(b.min.y) &&
                        std::isfinite(b.min.z) && std::isfinite(b.max.x) &&
                        std::isfinite(b.max.y) && std::isfinite(b.max.z);
    if (b.empty() || !finite) invalid(ctx_, "the asset's world-space bounds are not finite");
  }

  const tinygltf::Model& model_;
  LoadContext& ctx_;
  Scene scene_;
  AccessorReader reader_;
  PrimitiveConverter primitives_;
  MaterialConverter materials_;
  std::vector<int> meshRemap_;  // glTF mesh -> Scene::meshes; -1 not converted, -2 empty
  std::vector<std::size_t> meshTriangles_;  // per Scene::meshes
  std::vector<bool> onPath_;
  AnimationPose pose_;
  int variant_ = -1;
  std::vector<int> parents_;
  std::vector<std::optional<glm::mat4>> worldCache_;
  std::size_t visits_ = 0;
  std::size_t trianglesDrawn_ = 0;
};

}  // namespace

Scene buildScene(const tinygltf::Model& model, LoadContext& ctx) {
  return SceneBuilder(model, ctx).build();
}

}  // namespace lgh::gltf
