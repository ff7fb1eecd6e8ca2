#include "scene/gltf/geometry_decompression.hpp"

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <draco/compression/decode.h>
#include <fmt/format.h>
#include <meshoptimizer.h>

namespace lgh::gltf {
namespace {

// The largest element count a decoded stream may claim: what the triangle limit could ever use.
std::size_t elementLimit(const LoadContext& ctx) {
  const std::size_t maxTriangles = ctx.limits.maxTriangles;
  return maxTriangles < SIZE_MAX / 4 ? 3 * maxTriangles + 3 : SIZE_MAX;
}

// A new buffer + bufferView holding `bytes`; returns the bufferView index.
int appendBufferView(tinygltf::Model& model, std::vector<unsigned char> bytes) {
  tinygltf::Buffer buffer;
  buffer.data = std::move(bytes);
  tinygltf::BufferView view;
  view.buffer = static_cast<int>(model.buffers.size());
  view.byteOffset = 0;
  view.byteLength = buffer.data.size();
  model.buffers.push_back(std::move(buffer));
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

// The bytes of a bufferView, checked against its buffer.
std::pair<const unsigned char*, std::size_t> viewBytes(const tinygltf::Model& model, int index,
                                                       const LoadContext& ctx,
                                                       const std::string& owner) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.bufferViews.size()) {
    invalid(ctx, fmt::format("{}: bufferView {} does not exist", owner, index));
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(index)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
    invalid(ctx, fmt::format("{}: bufferView {} names buffer {}, which does not exist", owner,
                             index, view.buffer));
  }
  const auto& data = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
    invalid(ctx, fmt::format("{}: bufferView {} lies outside its buffer", owner, index));
  }
  return {data.data() + view.byteOffset, view.byteLength};
}

// ---- KHR_draco_mesh_compression -----------------------------------------------------------------

void pointAccessorAt(tinygltf::Model& model, int accessorIndex, int view, int componentType,
                     std::size_t count) {
  tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(accessorIndex)];
  accessor.bufferView = view;
  accessor.byteOffset = 0;
  accessor.componentType = componentType;
  accessor.normalized = false;
  accessor.count = count;
  accessor.sparse = {};
}

void decodeDracoAttribute(tinygltf::Model& model, const draco::Mesh& mesh, const std::string& name,
                          int uniqueId, int accessorIndex, const LoadContext& ctx,
                          const std::string& owner) {
  if (accessorIndex < 0 || static_cast<std::size_t>(accessorIndex) >= model.accessors.size()) {
    invalid(ctx, fmt::format("{}: attribute {} names accessor {}, which does not exist", owner,
                             name, accessorIndex));
  }
  const draco::PointAttribute* attribute = mesh.GetAttributeByUniqueId(uniqueId);
  if (attribute == nullptr) {
    invalid(ctx, fmt::format("{}: the Draco stream has no attribute {} (for {})", owner, uniqueId,
                             name));
  }
  const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(accessorIndex)];
  const int components =
      tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
  if (components <= 0 || components > 4) {
    invalid(ctx, fmt::format("{}: attribute {} has an unusable accessor type", owner, name));
  }
  const std::size_t points = mesh.num_points();
  const bool joints = name.rfind("JOINTS_", 0) == 0;
  const std::size_t componentBytes = joints ? 2 : 4;
  std::vector<unsigned char> bytes(points * static_cast<std::size_t>(components) * componentBytes);
  std::vector<float> value(static_cast<std::size_t>(components));
  for (std::size_t i = 0; i < points; ++i) {
    const auto index = attribute->mapped_index(draco::PointIndex(static_cast<std::uint32_t>(i)));
    if (!attribute->ConvertValue<float>(index, static_cast<std::int8_t>(components),
                                        value.data())) {
      invalid(ctx, fmt::format("{}: Draco attribute {} does not convert to {} floats", owner, name,
                               components));
    }
    for (int c = 0; c < components; ++c) {
      unsigned char* out =
          bytes.data() + (i * static_cast<std::size_t>(components) + c) * componentBytes;
      if (joints) {
        const auto joint = static_cast<std::uint16_t>(
            std::clamp(value[static_cast<std::size_t>(c)], 0.0F, 65535.0F));
        std::memcpy(out, &joint, 2);
      } else {
        std::memcpy(out, &value[static_cast<std::size_t>(c)], 4);
      }
    }
  }
  const int view = appendBufferView(model, std::move(bytes));
  pointAccessorAt(model, accessorIndex, view,
                  joints ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_FLOAT,
                  points);
}

void decodeDracoPrimitive(tinygltf::Model& model, tinygltf::Primitive& primitive,
                          const tinygltf::Value& extension, LoadContext& ctx,
                          const std::string& owner) {
  if (!extension.Has("bufferView") || !extension.Get("bufferView").IsInt() ||
      !extension.Has("attributes") || !extension.Get("attributes").IsObject()) {
    invalid(ctx,
            fmt::format("{}: KHR_draco_mesh_compression needs bufferView and attributes", owner));
  }
  const auto [data, length] =
      viewBytes(model, extension.Get("bufferView").GetNumberAsInt(), ctx, owner);
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), length);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok() || decoded.value() == nullptr) {
    invalid(ctx, fmt::format("{}: the Draco stream does not decode: {}", owner,
                             decoded.ok() ? "no mesh" : decoded.status().error_msg_string()));
  }
  const draco::Mesh& mesh = *decoded.value();
  const std::size_t limit = elementLimit(ctx);
  if (mesh.num_points() > limit || mesh.num_faces() > ctx.limits.maxTriangles) {
    tooLarge(ctx,
             fmt::format("{}: the Draco stream decodes to {} points and {} triangles, over the "
                         "limits",
                         owner, mesh.num_points(), mesh.num_faces()));
  }
  const tinygltf::Value& attributes = extension.Get("attributes");
  for (const std::string& name : attributes.Keys()) {
    const tinygltf::Value& id = attributes.Get(name);
    const auto target = primitive.attributes.find(name);
    if (!id.IsInt() || target == primitive.attributes.end()) continue;
    decodeDracoAttribute(model, mesh, name, id.GetNumberAsInt(), target->second, ctx, owner);
  }
  if (primitive.indices >= 0 &&
      static_cast<std::size_t>(primitive.indices) < model.accessors.size()) {
    std::vector<unsigned char> bytes(static_cast<std::size_t>(mesh.num_faces()) * 3 * 4);
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
      const draco::Mesh::Face& face = mesh.face(f);
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t index = face[k].value();
        std::memcpy(bytes.data() + (static_cast<std::size_t>(f.value()) * 3 + k) * 4, &index, 4);
      }
    }
    const int view = appendBufferView(model, std::move(bytes));
    pointAccessorAt(model, primitive.indices, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                    static_cast<std::size_t>(mesh.num_faces()) * 3);
  }
}

// ---- EXT_meshopt_compression --------------------------------------------------------------------

int intMember(const tinygltf::Value& object, const char* key, int fallback) {
  return object.Has(key) && object.Get(key).IsInt() ? object.Get(key).GetNumberAsInt() : fallback;
}

std::string stringMember(const tinygltf::Value& object, const char* key) {
  return object.Has(key) && object.Get(key).IsString() ? object.Get(key).Get<std::string>() : "";
}

void decodeMeshoptView(tinygltf::Model& model, int viewIndex, const tinygltf::Value& extension,
                       LoadContext& ctx) {
  const std::string owner =
      fmt::format("/bufferViews/{}/extensions/EXT_meshopt_compression", viewIndex);
  const int bufferIndex = intMember(extension, "buffer", -1);
  const int offset = intMember(extension, "byteOffset", 0);
  const int length = intMember(extension, "byteLength", -1);
  const int stride = intMember(extension, "byteStride", -1);
  const int count = intMember(extension, "count", -1);
  const std::string mode = stringMember(extension, "mode");
  const std::string filter = stringMember(extension, "filter");
  if (bufferIndex < 0 || static_cast<std::size_t>(bufferIndex) >= model.buffers.size() ||
      offset < 0 || length < 0 || stride <= 0 || count < 0) {
    invalid(ctx, fmt::format("{}: buffer, byteOffset, byteLength, byteStride and count must be "
                             "given and valid",
                             owner));
  }
  const auto& source = model.buffers[static_cast<std::size_t>(bufferIndex)].data;
  if (static_cast<std::size_t>(offset) > source.size() ||
      static_cast<std::size_t>(length) > source.size() - static_cast<std::size_t>(offset)) {
    invalid(ctx, fmt::format("{}: the compressed bytes lie outside buffer {}", owner, bufferIndex));
  }
  if (static_cast<std::size_t>(count) > elementLimit(ctx) || stride > 256) {
    tooLarge(ctx,
             fmt::format("{}: {} elements of {} bytes are over the limits", owner, count, stride));
  }
  const unsigned char* compressed = source.data() + offset;
  std::vector<unsigned char> bytes(static_cast<std::size_t>(count) *
                                   static_cast<std::size_t>(stride));
  int status = -1;
  if (mode == "ATTRIBUTES") {
    status = (stride % 4 == 0)
                 ? meshopt_decodeVertexBuffer(bytes.data(), static_cast<std::size_t>(count),
                                              static_cast<std::size_t>(stride), compressed,
                                              static_cast<std::size_t>(length))
                 : -1;
  } else if (mode == "TRIANGLES" || mode == "INDICES") {
    if (stride != 2 && stride != 4) {
      invalid(ctx, fmt::format("{}: index byteStride must be 2 or 4", owner));
    }
    if (mode == "TRIANGLES" && count % 3 != 0) {
      invalid(ctx, fmt::format("{}: TRIANGLES count {} is not a multiple of 3", owner, count));
    }
    status = mode == "TRIANGLES"
                 ? meshopt_decodeIndexBuffer(bytes.data(), static_cast<std::size_t>(count),
                                             static_cast<std::size_t>(stride), compressed,
                                             static_cast<std::size_t>(length))
                 : meshopt_decodeIndexSequence(bytes.data(), static_cast<std::size_t>(count),
                                               static_cast<std::size_t>(stride), compressed,
                                               static_cast<std::size_t>(length));
  } else {
    invalid(ctx, fmt::format("{}: unknown mode '{}'", owner, mode));
  }
  if (status != 0) invalid(ctx, fmt::format("{}: the compressed stream does not decode", owner));
  const auto elements = static_cast<std::size_t>(count);
  const auto elementStride = static_cast<std::size_t>(stride);
  if (filter == "OCTAHEDRAL" && (stride == 4 || stride == 8)) {
    meshopt_decodeFilterOct(bytes.data(), elements, elementStride);
  } else if (filter == "QUATERNION" && stride == 8) {
    meshopt_decodeFilterQuat(bytes.data(), elements, elementStride);
  } else if (filter == "EXPONENTIAL" && stride % 4 == 0) {
    meshopt_decodeFilterExp(bytes.data(), elements, elementStride);
  } else if (!filter.empty() && filter != "NONE") {
    invalid(ctx, fmt::format("{}: filter '{}' does not fit byteStride {}", owner, filter, stride));
  }
  tinygltf::Buffer decoded;
  decoded.data = std::move(bytes);
  tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(viewIndex)];
  view.buffer = static_cast<int>(model.buffers.size());
  view.byteOffset = 0;
  view.byteLength = decoded.data.size();
  view.byteStride = mode == "ATTRIBUTES" ? elementStride : 0;
  model.buffers.push_back(std::move(decoded));
}

}  // namespace

void decompressGeometry(tinygltf::Model& model, LoadContext& ctx) {
  for (std::size_t v = 0; v < model.bufferViews.size(); ++v) {
    const auto& extensions = model.bufferViews[v].extensions;
    for (const char* name : {"EXT_meshopt_compression", "KHR_meshopt_compression"}) {
      const auto it = extensions.find(name);
      if (it != extensions.end() && it->second.IsObject()) {
        const tinygltf::Value extension = it->second;
        decodeMeshoptView(model, static_cast<int>(v), extension, ctx);
        break;
      }
    }
  }
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
      const auto it = primitive.extensions.find("KHR_draco_mesh_compression");
      if (it == primitive.extensions.end() || !it->second.IsObject()) continue;
      const tinygltf::Value extension = it->second;
      const std::string owner = fmt::format("/meshes/{}/primitives/{}", m, p);
      decodeDracoPrimitive(model, primitive, extension, ctx, owner);
    }
  }
}

}  // namespace lgh::gltf
