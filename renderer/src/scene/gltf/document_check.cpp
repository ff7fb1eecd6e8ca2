#include "scene/gltf/document_check.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <map>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "lgh/base64.hpp"
#include "lgh/error.hpp"
#include "request/json_pointer.hpp"

namespace lgh::gltf {
namespace {

using json = nlohmann::json;

const json& emptyArray() {
  static const json empty = json::array();
  return empty;
}

const json& member(const json& object, const char* key) {
  if (!object.is_object()) return emptyArray();
  const auto it = object.find(key);
  return it == object.end() ? emptyArray() : *it;
}

std::uint64_t unsignedOr(const json& object, const char* key, std::uint64_t fallback) {
  const json& value = member(object, key);
  return value.is_number_integer() && value.get<std::int64_t>() >= 0 ? value.get<std::uint64_t>()
                                                                     : fallback;
}

std::uint64_t componentBytes(std::uint64_t componentType) {
  switch (componentType) {
    case 5120:
    case 5121:
      return 1;
    case 5122:
    case 5123:
      return 2;
    default:
      return 4;
  }
}

// Bytes of one element, with the column padding glTF requires for small matrices.
std::uint64_t elementBytes(const std::string& type, std::uint64_t component) {
  if (type == "SCALAR") return component;
  if (type == "VEC2") return 2 * component;
  if (type == "VEC3") return 3 * component;
  if (type == "VEC4" || (type == "MAT2" && component == 4)) return 4 * component;
  const auto padded = [](std::uint64_t bytes) { return (bytes + 3) / 4 * 4; };
  if (type == "MAT2") return 2 * padded(2 * component);
  if (type == "MAT3") return 3 * padded(3 * component);
  return 16 * component;  // MAT4: columns of 4 components never need padding
}

class DocumentChecker {
 public:
  DocumentChecker(const json& document, const DocumentContext& context)
      : document_(document), context_(context) {}

  void run() {
    checkExtensions();
    checkReferences();
    checkHierarchy();
    checkNodeTransforms();
    checkBuffers();
    checkBufferViews();
    checkAccessors();
    checkPrimitives();
  }

 private:
  const json& array(const char* name) const {
    const json& value = member(document_, name);
    return value.is_array() ? value : emptyArray();
  }

  [[noreturn]] void fail(const std::string& pointer, const std::string& problem) const {
    throw Error(ErrorCode::Invalid, fmt::format("invalid glTF: {} {}", pointer, problem),
                context_.displayName);
  }

  // --- Extensions ------------------------------------------------------------------------------

  void checkExtensions() const {
    std::set<std::string> used;
    for (const json& name : array("extensionsUsed")) used.insert(name.get<std::string>());
    const json& required = array("extensionsRequired");
    for (std::size_t i = 0; i < required.size(); ++i) {
      if (used.count(required[i].get<std::string>()) == 0) {
        fail(fmt::format("/extensionsRequired/{}", i),
             fmt::format("names {}, which /extensionsUsed does not list", required[i].dump()));
      }
    }
    // Extensions that change how the data reads cannot be optional.
    const json& usedList = array("extensionsUsed");
    for (std::size_t i = 0; i < usedList.size(); ++i) {
      const bool listedRequired = std::any_of(
          required.begin(), required.end(), [&](const json& name) { return name == usedList[i]; });
      if (usedList[i] == "KHR_mesh_quantization" && !listedRequired) {
        fail(fmt::format("/extensionsUsed/{}", i),
             "names KHR_mesh_quantization, which cannot be optional: list it in "
             "/extensionsRequired too");
      }
    }
    // Every "extensions" object anywhere but inside extras: its members must be declared.
    struct Frame {
      const json* value;
      std::string pointer;
    };
    std::vector<Frame> stack{{&document_, ""}};
    while (!stack.empty()) {
      const Frame frame = std::move(stack.back());
      stack.pop_back();
      if (frame.value->is_array()) {
        for (std::size_t i = 0; i < frame.value->size(); ++i) {
          const json& item = (*frame.value)[i];
          if (item.is_structured()) {
            stack.push_back({&item, fmt::format("{}/{}", frame.pointer, i)});
          }
        }
        continue;
      }
      for (const auto& [key, value] : frame.value->items()) {
        if (key == "extras" || !value.is_structured()) continue;
        const std::string pointer = frame.pointer + "/" + escapePointerToken(key);
        if (key == "extensions" && value.is_object()) {
          for (const auto& [name, extension] : value.items()) {
            if (used.count(name) == 0) {
              fail(pointer + "/" + escapePointerToken(name),
                   "uses an extension that /extensionsUsed does not declare");
            }
          }
        }
        stack.push_back({&value, pointer});
      }
    }
  }

  // --- References ----------------------------------------------------------------------------

  // `object[key]`, when present, must be an index into `targets`.
  void reference(const json& object, const char* key, const json& targets, const char* what,
                 const std::string& pointer) const {
    if (!object.is_object() || !object.contains(key)) return;
    indexInto(object[key], targets, what, pointer + "/" + key);
  }

  void indexInto(const json& value, const json& targets, const char* what,
                 const std::string& pointer) const {
    if (!value.is_number_integer() || value.get<std::int64_t>() < 0) {
      fail(pointer, "must be a non-negative integer");
    }
    const auto index = value.get<std::uint64_t>();
    if (index >= targets.size()) {
      fail(pointer, fmt::format("names {} {}, which does not exist (the asset has {})", what, index,
                                targets.size()));
    }
  }

  void indicesInto(const json& object, const char* key, const json& targets, const char* what,
                   const std::string& pointer) const {
    const json& values = member(object, key);
    if (!values.is_array()) return;
    for (std::size_t i = 0; i < values.size(); ++i) {
      indexInto(values[i], targets, what, fmt::format("{}/{}/{}", pointer, key, i));
    }
  }

  void attributeReferences(const json& attributes, const std::string& pointer) const {
    if (!attributes.is_object()) return;
    for (const auto& [name, accessor] : attributes.items()) {
      indexInto(accessor, array("accessors"), "accessor", pointer + "/" + escapePointerToken(name));
    }
  }

  void checkReferences() const {
    const json& nodes = array("nodes");
    const json& accessors = array("accessors");
    const json& bufferViews = array("bufferViews");
    reference(document_, "scene", array("scenes"), "scene", "");
    const json& scenes = array("scenes");
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      indicesInto(scenes[i], "nodes", nodes, "node", fmt::format("/scenes/{}", i));
    }
    const json& lights =
        member(member(member(document_, "extensions"), "KHR_lights_punctual"), "lights");
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const std::string pointer = fmt::format("/nodes/{}", i);
      reference(nodes[i], "camera", array("cameras"), "camera", pointer);
      reference(nodes[i], "mesh", array("meshes"), "mesh", pointer);
      reference(nodes[i], "skin", array("skins"), "skin", pointer);
      indicesInto(nodes[i], "children", nodes, "node", pointer);
      reference(member(member(nodes[i], "extensions"), "KHR_lights_punctual"), "light",
                lights.is_array() ? lights : emptyArray(), "light",
                pointer + "/extensions/KHR_lights_punctual");
    }
    const json& meshes = array("meshes");
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const json& primitives = member(meshes[m], "primitives");
      for (std::size_t p = 0; p < primitives.size(); ++p) {
        const std::string pointer = fmt::format("/meshes/{}/primitives/{}", m, p);
        attributeReferences(member(primitives[p], "attributes"), pointer + "/attributes");
        reference(primitives[p], "indices", accessors, "accessor", pointer);
        reference(primitives[p], "material", array("materials"), "material", pointer);
        const json& targets = member(primitives[p], "targets");
        for (std::size_t t = 0; t < targets.size(); ++t) {
          attributeReferences(targets[t], fmt::format("{}/targets/{}", pointer, t));
        }
      }
    }
    for (std::size_t i = 0; i < accessors.size(); ++i) {
      const std::string pointer = fmt::format("/accessors/{}", i);
      reference(accessors[i], "bufferView", bufferViews, "bufferView", pointer);
      const json& sparse = member(accessors[i], "sparse");
      reference(member(sparse, "indices"), "bufferView", bufferViews, "bufferView",
                pointer + "/sparse/indices");
      reference(member(sparse, "values"), "bufferView", bufferViews, "bufferView",
                pointer + "/sparse/values");
    }
    for (std::size_t i = 0; i < bufferViews.size(); ++i) {
      reference(bufferViews[i], "buffer", array("buffers"), "buffer",
                fmt::format("/bufferViews/{}", i));
    }
    const json& images = array("images");
    for (std::size_t i = 0; i < images.size(); ++i) {
      reference(images[i], "bufferView", bufferViews, "bufferView", fmt::format("/images/{}", i));
    }
    const json& textures = array("textures");
    for (std::size_t i = 0; i < textures.size(); ++i) {
      const std::string pointer = fmt::format("/textures/{}", i);
      reference(textures[i], "source", images, "image", pointer);
      reference(textures[i], "sampler", array("samplers"), "sampler", pointer);
    }
    checkMaterialReferences();
    checkSkinAndAnimationReferences();
  }

  void checkMaterialReferences() const {
    const json& materials = array("materials");
    for (std::size_t i = 0; i < materials.size(); ++i) {
      const std::string pointer = fmt::format("/materials/{}", i);
      const json& pbr = member(materials[i], "pbrMetallicRoughness");
      for (const char* texture : {"baseColorTexture", "metallicRoughnessTexture"}) {
        reference(member(pbr, texture), "index", array("textures"), "texture",
                  fmt::format("{}/pbrMetallicRoughness/{}", pointer, texture));
      }
      for (const char* texture : {"normalTexture", "occlusionTexture", "emissiveTexture"}) {
        reference(member(materials[i], texture), "index", array("textures"), "texture",
                  fmt::format("{}/{}", pointer, texture));
      }
    }
  }

  void checkSkinAndAnimationReferences() const {
    const json& skins = array("skins");
    for (std::size_t i = 0; i < skins.size(); ++i) {
      const std::string pointer = fmt::format("/skins/{}", i);
      reference(skins[i], "inverseBindMatrices", array("accessors"), "accessor", pointer);
      reference(skins[i], "skeleton", array("nodes"), "node", pointer);
      indicesInto(skins[i], "joints", array("nodes"), "node", pointer);
    }
    const json& animations = array("animations");
    for (std::size_t a = 0; a < animations.size(); ++a) {
      const std::string pointer = fmt::format("/animations/{}", a);
      const json& samplers = member(animations[a], "samplers");
      for (std::size_t s = 0; s < samplers.size(); ++s) {
        const std::string samplerPointer = fmt::format("{}/samplers/{}", pointer, s);
        reference(samplers[s], "input", array("accessors"), "accessor", samplerPointer);
        reference(samplers[s], "output", array("accessors"), "accessor", samplerPointer);
      }
      const json& channels = member(animations[a], "channels");
      for (std::size_t c = 0; c < channels.size(); ++c) {
        const std::string channelPointer = fmt::format("{}/channels/{}", pointer, c);
        reference(channels[c], "sampler", samplers.is_array() ? samplers : emptyArray(),
                  "animation sampler", channelPointer);
        reference(member(channels[c], "target"), "node", array("nodes"), "node",
                  channelPointer + "/target");
      }
    }
  }

  // --- Node hierarchy --------------------------------------------------------------------------

  void checkHierarchy() const {
    const json& nodes = array("nodes");
    constexpr std::size_t kNone = static_cast<std::size_t>(-1);
    std::vector<std::size_t> parent(nodes.size(), kNone);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const json& children = member(nodes[i], "children");
      std::set<std::size_t> seen;
      for (std::size_t k = 0; k < children.size(); ++k) {
        const auto child = children[k].get<std::size_t>();
        const std::string pointer = fmt::format("/nodes/{}/children/{}", i, k);
        if (!seen.insert(child).second) fail(pointer, fmt::format("names node {} twice", child));
        if (parent[child] != kNone) {
          fail(pointer, fmt::format("names node {}, already a child of /nodes/{}: a node has at "
                                    "most one parent",
                                    child, parent[child]));
        }
        parent[child] = i;
      }
    }
    const json& scenes = array("scenes");
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      const json& roots = member(scenes[s], "nodes");
      std::set<std::size_t> seen;
      for (std::size_t k = 0; k < roots.size(); ++k) {
        const auto node = roots[k].get<std::size_t>();
        const std::string pointer = fmt::format("/scenes/{}/nodes/{}", s, k);
        if (!seen.insert(node).second) fail(pointer, fmt::format("names node {} twice", node));
        if (parent[node] != kNone) {
          fail(pointer, fmt::format("names node {}, a child of /nodes/{}: a scene lists root "
                                    "nodes only",
                                    node, parent[node]));
        }
      }
    }
    // One parent each: following parents from any node either ends at a root or loops.
    enum class State : std::uint8_t { Unvisited, OnPath, Done };
    std::vector<State> state(nodes.size(), State::Unvisited);
    for (std::size_t start = 0; start < nodes.size(); ++start) {
      std::vector<std::size_t> path;
      std::size_t node = start;
      while (node != kNone && state[node] == State::Unvisited) {
        state[node] = State::OnPath;
        path.push_back(node);
        node = parent[node];
      }
      if (node != kNone && state[node] == State::OnPath) {
        fail(fmt::format("/nodes/{}", node), "is its own ancestor: the node hierarchy has a loop");
      }
      for (std::size_t visited : path) state[visited] = State::Done;
    }
  }

  void checkNodeTransforms() const {
    const json& nodes = array("nodes");
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const json& matrix = member(nodes[i], "matrix");
      if (!matrix.is_array() || matrix.size() != 16) continue;
      const std::string pointer = fmt::format("/nodes/{}", i);
      for (const char* trs : {"translation", "rotation", "scale"}) {
        if (nodes[i].contains(trs)) {
          fail(pointer, fmt::format("has both matrix and {}", trs));
        }
      }
      // Column-major: the last row is elements 3, 7, 11 and 15.
      const bool affine = matrix[3] == 0 && matrix[7] == 0 && matrix[11] == 0 && matrix[15] == 1;
      if (!affine) {
        fail(pointer + "/matrix",
             "is not a translation/rotation/scale: its last row must be "
             "0, 0, 0, 1");
      }
    }
  }

  // --- Buffers, bufferViews, accessors ---------------------------------------------------------

  void checkBuffers() const {
    const json& buffers = array("buffers");
    for (std::size_t i = 0; i < buffers.size(); ++i) {
      const std::string pointer = fmt::format("/buffers/{}", i);
      const std::uint64_t byteLength = unsignedOr(buffers[i], "byteLength", 0);
      const json& uri = member(buffers[i], "uri");
      if (!uri.is_string()) {
        // EXT_meshopt_compression's fallback buffers hold no data: only decoded bufferViews lie
        // in them (geometry_decompression fills those).
        if (!isMeshoptFallback(buffers[i])) checkGlbBuffer(i, byteLength, pointer);
        continue;
      }
      const std::string_view text = uri.get_ref<const std::string&>();
      if (!text.starts_with("data:")) continue;
      const std::size_t comma = text.find(',');
      const std::string_view header = text.substr(0, comma);
      if (comma == std::string_view::npos || !header.ends_with(";base64")) {
        fail(pointer + "/uri", "is a data: URI that is not base64 (data:[type];base64,...)");
      }
      const std::string_view payload = text.substr(comma + 1);
      const auto decoded = base64::decodedSize(payload);
      const bool alphabet = std::all_of(payload.begin(), payload.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '+' || c == '/' || c == '=';
      });
      if (!decoded || !alphabet) fail(pointer + "/uri", "is a data: URI with invalid base64");
      if (*decoded != byteLength) {
        fail(pointer,
             fmt::format("has a data: URI of {} bytes, but byteLength {}", *decoded, byteLength));
      }
    }
  }

  static bool isMeshoptFallback(const json& buffer) {
    const json& extensions = member(buffer, "extensions");
    for (const char* name : {"EXT_meshopt_compression", "KHR_meshopt_compression"}) {
      const json& extension = member(extensions, name);
      const json& fallback = member(extension, "fallback");
      if (fallback.is_boolean() && fallback.get<bool>()) return true;
    }
    return false;
  }

  void checkGlbBuffer(std::size_t index, std::uint64_t byteLength,
                      const std::string& pointer) const {
    if (!context_.glbBinBytes || index != 0) {
      fail(pointer, "has no uri: only the first buffer of a .glb may leave it out");
    }
    if (*context_.glbBinBytes == 0) {
      fail(pointer, "has no uri, and the GLB has no BIN chunk to take its bytes from");
    }
    if (*context_.glbBinBytes < byteLength) {
      fail(pointer, fmt::format("has byteLength {}, more than the {} bytes of the GLB's BIN chunk",
                                byteLength, *context_.glbBinBytes));
    }
  }

  void checkBufferViews() const {
    const json& views = array("bufferViews");
    const json& buffers = array("buffers");
    for (std::size_t i = 0; i < views.size(); ++i) {
      const auto buffer = views[i]["buffer"].get<std::size_t>();
      const std::uint64_t offset = unsignedOr(views[i], "byteOffset", 0);
      const std::uint64_t length = unsignedOr(views[i], "byteLength", 0);
      const std::uint64_t bufferLength = unsignedOr(buffers[buffer], "byteLength", 0);
      if (offset > bufferLength || length > bufferLength - offset) {
        fail(fmt::format("/bufferViews/{}", i),
             fmt::format("(byteOffset {}, byteLength {}) reaches past the end of /buffers/{} "
                         "(byteLength {})",
                         offset, length, buffer, bufferLength));
      }
    }
  }

  void checkAccessors() const {
    const json& accessors = array("accessors");
    const json& views = array("bufferViews");
    for (std::size_t i = 0; i < accessors.size(); ++i) {
      const json& accessor = accessors[i];
      const std::string pointer = fmt::format("/accessors/{}", i);
      const std::uint64_t component =
          componentBytes(accessor["componentType"].get<std::uint64_t>());
      const std::uint64_t element = elementBytes(accessor["type"].get<std::string>(), component);
      const std::uint64_t count = accessor["count"].get<std::uint64_t>();
      const std::uint64_t offset = unsignedOr(accessor, "byteOffset", 0);
      if (accessor.contains("bufferView")) {
        const auto viewIndex = accessor["bufferView"].get<std::size_t>();
        const json& view = views[viewIndex];
        if (offset % component != 0) {
          fail(pointer + "/byteOffset",
               fmt::format("{} is not a multiple of the component size {}", offset, component));
        }
        if ((unsignedOr(view, "byteOffset", 0) + offset) % component != 0) {
          fail(pointer + "/byteOffset",
               fmt::format("with /bufferViews/{}/byteOffset does not align the data to the "
                           "component size {}",
                           viewIndex, component));
        }
        const std::uint64_t declaredStride = unsignedOr(view, "byteStride", 0);
        if (declaredStride != 0 && declaredStride < element) {
          fail(pointer, fmt::format("has elements of {} bytes, more than the byteStride {} of "
                                    "/bufferViews/{}",
                                    element, declaredStride, viewIndex));
        }
        const std::uint64_t stride = declaredStride != 0 ? declaredStride : element;
        const std::uint64_t viewLength = unsignedOr(view, "byteLength", 0);
        if (offset + stride * (count - 1) + element > viewLength) {
          fail(pointer, fmt::format("({} elements of {} bytes, stride {}, byteOffset {}) reaches "
                                    "past the end of /bufferViews/{} (byteLength {})",
                                    count, element, stride, offset, viewIndex, viewLength));
        }
      }
      checkSparse(accessor, pointer, count, element);
    }
  }

  void checkSparse(const json& accessor, const std::string& pointer, std::uint64_t count,
                   std::uint64_t element) const {
    const json& sparse = member(accessor, "sparse");
    if (!sparse.is_object()) return;
    const std::uint64_t sparseCount = sparse["count"].get<std::uint64_t>();
    if (sparseCount > count) {
      fail(pointer + "/sparse/count",
           fmt::format("{} is more than the accessor's count {}", sparseCount, count));
    }
    const json& views = array("bufferViews");
    const auto region = [&](const json& part, std::uint64_t itemBytes, const char* name) {
      const auto viewIndex = part["bufferView"].get<std::size_t>();
      const std::uint64_t offset = unsignedOr(part, "byteOffset", 0);
      const std::uint64_t viewLength = unsignedOr(views[viewIndex], "byteLength", 0);
      if (offset + sparseCount * itemBytes > viewLength) {
        fail(fmt::format("{}/sparse/{}", pointer, name),
             fmt::format("({} items of {} bytes from byteOffset {}) reach past the end of "
                         "/bufferViews/{} (byteLength {})",
                         sparseCount, itemBytes, offset, viewIndex, viewLength));
      }
    };
    const json& indices = sparse["indices"];
    region(indices, componentBytes(indices["componentType"].get<std::uint64_t>()), "indices");
    region(sparse["values"], element, "values");
  }

  // --- Primitives ------------------------------------------------------------------------------

  void checkPrimitives() const {
    const json& meshes = array("meshes");
    std::map<std::size_t, std::pair<std::size_t, std::string>> vertexViews;  // view -> accessor
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const json& primitives = member(meshes[m], "primitives");
      for (std::size_t p = 0; p < primitives.size(); ++p) {
        const std::string pointer = fmt::format("/meshes/{}/primitives/{}", m, p);
        // The validator's MESH_PRIMITIVES_UNEQUAL_TARGETS_COUNT: morph weights apply per mesh.
        const std::size_t targets = member(primitives[p], "targets").size();
        const std::size_t firstTargets = member(primitives[0], "targets").size();
        if (targets != firstTargets) {
          fail(pointer, fmt::format("has {} morph target(s), but /meshes/{}/primitives/0 has {}: "
                                    "every primitive of a mesh must have the same number",
                                    targets, m, firstTargets));
        }
        const json& attributes = member(primitives[p], "attributes");
        checkSemanticSets(attributes, pointer + "/attributes");
        checkAttributeCounts(attributes, pointer + "/attributes");
        checkTexCoordsOfMaterial(primitives[p], attributes, pointer);
        checkSharedVertexViews(attributes, pointer + "/attributes", vertexViews);
      }
    }
  }

  // TEXCOORD_n, COLOR_n, JOINTS_n and WEIGHTS_n count up from 0 without gaps.
  void checkSemanticSets(const json& attributes, const std::string& pointer) const {
    for (const std::string prefix : {"TEXCOORD_", "COLOR_", "JOINTS_", "WEIGHTS_"}) {
      std::set<int> sets;
      for (const auto& [name, accessor] : attributes.items()) {
        if (!name.starts_with(prefix)) continue;
        const std::string digits = name.substr(prefix.size());
        const bool number = !digits.empty() && digits.size() < 4 &&
                            std::all_of(digits.begin(), digits.end(), ::isdigit);
        if (number) sets.insert(std::stoi(digits));
      }
      for (int set : sets) {
        if (set > 0 && sets.count(set - 1) == 0) {
          fail(pointer, fmt::format("has {}{} without {}{}", prefix, set, prefix, set - 1));
        }
      }
    }
  }

  void checkAttributeCounts(const json& attributes, const std::string& pointer) const {
    const json& accessors = array("accessors");
    const auto position = attributes.find("POSITION");
    if (position == attributes.end()) return;
    const auto expected = accessors[position->get<std::size_t>()]["count"].get<std::uint64_t>();
    for (const auto& [name, accessor] : attributes.items()) {
      const auto count = accessors[accessor.get<std::size_t>()]["count"].get<std::uint64_t>();
      if (count != expected) {
        fail(pointer + "/" + escapePointerToken(name),
             fmt::format("names an accessor of {} elements, but POSITION has {}", count, expected));
      }
    }
  }

  void checkTexCoordsOfMaterial(const json& primitive, const json& attributes,
                                const std::string& pointer) const {
    if (!primitive.contains("material")) return;
    const json& material = array("materials")[primitive["material"].get<std::size_t>()];
    const json& pbr = member(material, "pbrMetallicRoughness");
    const std::vector<std::pair<const char*, const json*>> textures = {
        {"baseColorTexture", &member(pbr, "baseColorTexture")},
        {"metallicRoughnessTexture", &member(pbr, "metallicRoughnessTexture")},
        {"normalTexture", &member(material, "normalTexture")},
        {"occlusionTexture", &member(material, "occlusionTexture")},
        {"emissiveTexture", &member(material, "emissiveTexture")}};
    for (const auto& [name, info] : textures) {
      if (!info->is_object()) continue;
      const std::uint64_t set = unsignedOr(*info, "texCoord", 0);
      if (!attributes.contains(fmt::format("TEXCOORD_{}", set))) {
        fail(pointer + "/material",
             fmt::format("names /materials/{}, whose {} reads TEXCOORD_{}, which this primitive "
                         "does not have",
                         primitive["material"].get<std::size_t>(), name, set));
      }
    }
  }

  // A bufferView that holds several vertex attributes must say how they interleave.
  void checkSharedVertexViews(
      const json& attributes, const std::string& pointer,
      std::map<std::size_t, std::pair<std::size_t, std::string>>& vertexViews) const {
    const json& accessors = array("accessors");
    const json& views = array("bufferViews");
    for (const auto& [name, accessor] : attributes.items()) {
      const auto index = accessor.get<std::size_t>();
      if (!accessors[index].contains("bufferView")) continue;
      const auto view = accessors[index]["bufferView"].get<std::size_t>();
      const std::string attribute = pointer + "/" + escapePointerToken(name);
      const auto [it, first] = vertexViews.try_emplace(view, index, attribute);
      if (first || it->second.first == index || views[view].contains("byteStride")) continue;
      fail(attribute, fmt::format("names /accessors/{}, which shares /bufferViews/{} with "
                                  "/accessors/{} ({}): a bufferView of several vertex attributes "
                                  "needs a byteStride",
                                  index, view, it->second.first, it->second.second));
    }
  }

  const json& document_;
  const DocumentContext& context_;
};

}  // namespace

void checkDocument(const nlohmann::json& document, const DocumentContext& context) {
  DocumentChecker(document, context).run();
}

}  // namespace lgh::gltf
