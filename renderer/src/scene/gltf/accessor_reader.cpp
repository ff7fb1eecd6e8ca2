#include "scene/gltf/accessor_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include <fmt/format.h>

namespace lgh::gltf {
namespace {

const char* componentTypeName(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT:
      return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "FLOAT";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE:
      return "DOUBLE";
    default:
      return "unknown";
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "unknown";
  }
}

bool typeAllowed(Semantic semantic, int type) {
  switch (semantic) {
    case Semantic::Position:
    case Semantic::Normal:
      return type == TINYGLTF_TYPE_VEC3;
    case Semantic::Tangent:
      return type == TINYGLTF_TYPE_VEC4;
    case Semantic::TexCoord:
      return type == TINYGLTF_TYPE_VEC2;
    case Semantic::Color:
      return type == TINYGLTF_TYPE_VEC3 || type == TINYGLTF_TYPE_VEC4;
    case Semantic::Indices:
    case Semantic::AnimationInput:
      return type == TINYGLTF_TYPE_SCALAR;
    case Semantic::MorphDelta:
      return type == TINYGLTF_TYPE_VEC3;
    case Semantic::Joints:
    case Semantic::Weights:
      return type == TINYGLTF_TYPE_VEC4;
    case Semantic::Matrix:
      return type == TINYGLTF_TYPE_MAT4;
    case Semantic::AnimationOutput:
      return type == TINYGLTF_TYPE_SCALAR || type == TINYGLTF_TYPE_VEC3 ||
             type == TINYGLTF_TYPE_VEC4;
  }
  return false;
}

// The glTF 2.0 tables of accessor formats per attribute, widened by KHR_mesh_quantization.
bool formatAllowed(Semantic semantic, int componentType, bool normalized, bool quantized) {
  const int ct = componentType;
  const bool isFloat = ct == TINYGLTF_COMPONENT_TYPE_FLOAT && !normalized;
  const bool unsignedNormalized = normalized && (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                                 ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  const bool signedNormalized =
      normalized && (ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT);
  const bool smallInteger =
      ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
      ct == TINYGLTF_COMPONENT_TYPE_SHORT || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  switch (semantic) {
    case Semantic::Position:
      return isFloat || (quantized && smallInteger);
    case Semantic::Normal:
    case Semantic::Tangent:
      return isFloat || (quantized && signedNormalized);
    case Semantic::TexCoord:
      return isFloat || unsignedNormalized || (quantized && smallInteger);
    case Semantic::Color:
      return isFloat || unsignedNormalized;
    case Semantic::Indices:
      return !normalized && (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                             ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                             ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
    case Semantic::MorphDelta:
      return isFloat || (quantized && (signedNormalized || smallInteger));
    case Semantic::Joints:
      return !normalized && (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                             ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    case Semantic::Weights:
      return isFloat || unsignedNormalized;
    case Semantic::Matrix:
    case Semantic::AnimationInput:
      return isFloat;
    case Semantic::AnimationOutput:
      return isFloat || unsignedNormalized || signedNormalized;
  }
  return false;
}

const char* allowedFormats(Semantic semantic) {
  switch (semantic) {
    case Semantic::Position:
    case Semantic::Normal:
      return "VEC3 of FLOAT";
    case Semantic::Tangent:
      return "VEC4 of FLOAT";
    case Semantic::TexCoord:
      return "VEC2 of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT";
    case Semantic::Color:
      return "VEC3/VEC4 of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT";
    case Semantic::Indices:
      return "SCALAR of UNSIGNED_BYTE/UNSIGNED_SHORT/UNSIGNED_INT";
    case Semantic::MorphDelta:
      return "VEC3 of FLOAT";
    case Semantic::Joints:
      return "VEC4 of UNSIGNED_BYTE/UNSIGNED_SHORT";
    case Semantic::Weights:
      return "VEC4 of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT";
    case Semantic::Matrix:
      return "MAT4 of FLOAT";
    case Semantic::AnimationInput:
      return "SCALAR of FLOAT";
    case Semantic::AnimationOutput:
      return "SCALAR/VEC3/VEC4 of FLOAT or normalized integers";
  }
  return "?";
}

std::size_t componentSize(int componentType) {
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(componentType));
  return size > 0 ? static_cast<std::size_t>(size) : 0;
}

double readComponent(const std::uint8_t* p, int componentType) {
  auto load = [p](auto value) {
    std::memcpy(&value, p, sizeof(value));
    return static_cast<double>(value);
  };
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return load(std::int8_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return load(std::uint8_t{});
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return load(std::int16_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return load(std::uint16_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return load(std::uint32_t{});
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load(float{});
    default:
      return 0.0;
  }
}

// glTF's normalised integer decoding (signed values clamp at -1).
float toFloat(double value, int componentType, bool normalized) {
  if (!normalized) return static_cast<float>(value);
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return std::max(static_cast<float>(value / 127.0), -1.0F);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return static_cast<float>(value / 255.0);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return std::max(static_cast<float>(value / 32767.0), -1.0F);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return static_cast<float>(value / 65535.0);
    default:
      return static_cast<float>(value);
  }
}

}  // namespace

// Element data of one accessor after every check: element i starts at data + i * stride.
struct AccessorReader::ElementSpan {
  const std::uint8_t* data = nullptr;  // nullptr: no bufferView, all zeros (glTF's rule)
  std::size_t stride = 0;
  std::size_t count = 0;
  int components = 0;
  int componentType = 0;
  bool normalized = false;
};

AccessorReader::AccessorReader(const tinygltf::Model& model, LoadContext& ctx, bool quantized)
    : model_(model), ctx_(ctx), quantized_(quantized) {}

std::vector<float> AccessorReader::readFloats(int index, Semantic semantic,
                                              const std::string& owner, int* components) const {
  const ElementSpan span = checkedSpan(index, semantic, owner);
  std::vector<float> values(span.count * static_cast<std::size_t>(span.components), 0.0F);
  forEachComponent(span, [&](std::size_t slot, double value) {
    values[slot] = toFloat(value, span.componentType, span.normalized);
  });
  applySparse(index, span, owner, [&](std::size_t slot, double value) {
    values[slot] = toFloat(value, span.componentType, span.normalized);
  });
  *components = span.components;
  checkFinite(values, index, owner, span.components);
  checkDeclaredBounds(values, index, semantic, owner, span);
  return values;
}

void AccessorReader::checkFinite(const std::vector<float>& values, int index,
                                 const std::string& owner, int components) const {
  const auto bad =
      std::find_if(values.begin(), values.end(), [](float value) { return !std::isfinite(value); });
  if (bad == values.end()) return;
  const auto slot = static_cast<std::size_t>(bad - values.begin());
  invalid(ctx_, fmt::format("{}: /accessors/{} holds a non-finite value (NaN or Inf) at element "
                            "{}",
                            owner, index, slot / static_cast<std::size_t>(components)));
}

// accessor.min and max describe the data; lghd never reads them (it computes bounds from the
// data), so declared bounds that are wrong or missing cannot mislead it: a warning, as the
// Khronos validator reports them as errors.
void AccessorReader::checkDeclaredBounds(const std::vector<float>& values, int index,
                                         Semantic semantic, const std::string& owner,
                                         const ElementSpan& span) const {
  const tinygltf::Accessor& accessor = accessorAt(index, owner);
  const auto components = static_cast<std::size_t>(span.components);
  if (accessor.minValues.empty() || accessor.maxValues.empty()) {
    if (semantic == Semantic::Position) {
      ctx_.warnOnce(
          fmt::format("{}: /accessors/{} declares no min/max, which POSITION needs; "
                      "bounds computed from the data",
                      owner, index));
    }
    return;
  }
  // Normalized integers declare their bounds in integer units; only plain values compare.
  if (span.normalized || accessor.minValues.size() != components ||
      accessor.maxValues.size() != components || values.empty()) {
    return;
  }
  for (std::size_t c = 0; c < components; ++c) {
    float low = values[c];
    float high = values[c];
    for (std::size_t i = c; i < values.size(); i += components) {
      low = std::min(low, values[i]);
      high = std::max(high, values[i]);
    }
    if (low != static_cast<float>(accessor.minValues[c]) ||
        high != static_cast<float>(accessor.maxValues[c])) {
      ctx_.warnOnce(
          fmt::format("{}: /accessors/{} declares min/max that do not match its data "
                      "(component {}: declared {} .. {}, actual {} .. {}); bounds "
                      "computed from the data",
                      owner, index, c, accessor.minValues[c], accessor.maxValues[c], low, high));
      return;
    }
  }
}

std::vector<std::uint32_t> AccessorReader::readIndices(int index, const std::string& owner) const {
  const ElementSpan span = checkedSpan(index, Semantic::Indices, owner);
  std::vector<std::uint32_t> values(span.count, 0);
  auto store = [&](std::size_t slot, double value) {
    values[slot] = static_cast<std::uint32_t>(value);
  };
  forEachComponent(span, store);
  applySparse(index, span, owner, store);
  return values;
}

std::size_t AccessorReader::elementCount(int index, const std::string& owner) const {
  return accessorAt(index, owner).count;
}

const tinygltf::Accessor& AccessorReader::accessorAt(int index, const std::string& owner) const {
  if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size()) {
    invalid(ctx_, fmt::format("{}: accessor {} does not exist", owner, index));
  }
  return model_.accessors[static_cast<std::size_t>(index)];
}

std::pair<const std::uint8_t*, std::size_t> AccessorReader::bufferViewBytes(
    int index, const std::string& owner) const {
  if (index < 0 || static_cast<std::size_t>(index) >= model_.bufferViews.size()) {
    invalid(ctx_, fmt::format("{}: bufferView {} does not exist", owner, index));
  }
  const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(index)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size()) {
    invalid(ctx_, fmt::format("{}: /bufferViews/{} names buffer {}, which does not exist", owner,
                              index, view.buffer));
  }
  const std::vector<unsigned char>& data =
      model_.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
    invalid(ctx_,
            fmt::format("{}: /bufferViews/{} (offset {}, length {}) lies outside /buffers/{} "
                        "({} bytes)",
                        owner, index, view.byteOffset, view.byteLength, view.buffer, data.size()));
  }
  return {data.data() + view.byteOffset, view.byteLength};
}

void AccessorReader::checkFormat(const tinygltf::Accessor& accessor, int index, Semantic semantic,
                                 const std::string& owner) const {
  if (typeAllowed(semantic, accessor.type) &&
      formatAllowed(semantic, accessor.componentType, accessor.normalized, quantized_)) {
    return;
  }
  invalid(ctx_, fmt::format("{}: /accessors/{} is {} of {}{}; glTF requires {}", owner, index,
                            typeName(accessor.type), accessor.normalized ? "normalized " : "",
                            componentTypeName(accessor.componentType), allowedFormats(semantic)));
}

AccessorReader::ElementSpan AccessorReader::checkedSpan(int index, Semantic semantic,
                                                        const std::string& owner) const {
  const tinygltf::Accessor& accessor = accessorAt(index, owner);
  checkFormat(accessor, index, semantic, owner);
  checkCount(accessor.count, owner, index);
  ElementSpan span;
  span.count = accessor.count;
  span.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
  span.componentType = accessor.componentType;
  span.normalized = accessor.normalized;
  const std::size_t elementSize = componentSize(accessor.componentType) * span.components;
  if (accessor.bufferView < 0) return span;  // zeros, maybe replaced by sparse values
  const auto [bytes, length] = bufferViewBytes(accessor.bufferView, owner);
  const std::size_t declaredStride =
      model_.bufferViews[static_cast<std::size_t>(accessor.bufferView)].byteStride;
  span.stride = declaredStride != 0 ? declaredStride : elementSize;
  if (span.stride < elementSize) {
    invalid(ctx_, fmt::format("{}: /accessors/{} has byteStride {} smaller than its {}-byte "
                              "elements",
                              owner, index, span.stride, elementSize));
  }
  // offset + stride * (count - 1) + elementSize <= length, without overflow.
  const bool fits = accessor.byteOffset <= length && elementSize <= length - accessor.byteOffset &&
                    span.count - 1 <= (length - accessor.byteOffset - elementSize) / span.stride;
  if (!fits) {
    invalid(ctx_, fmt::format("{}: /accessors/{} ({} elements of {} bytes, stride {}, offset {}) "
                              "reads past the end of /bufferViews/{} ({} bytes)",
                              owner, index, span.count, elementSize, span.stride,
                              accessor.byteOffset, accessor.bufferView, length));
  }
  span.data = bytes + accessor.byteOffset;
  return span;
}

void AccessorReader::checkCount(std::size_t count, const std::string& owner, int index) const {
  const std::size_t maxTriangles = ctx_.limits.maxTriangles;
  const std::size_t limit = maxTriangles < SIZE_MAX / 4 ? 3 * maxTriangles + 3 : SIZE_MAX;
  if (count > limit) {
    tooLarge(ctx_, fmt::format("{}: /accessors/{} has {} elements, more than the triangle limit "
                               "allows ({})",
                               owner, index, count, limit));
  }
}

template <typename Store>
void AccessorReader::forEachComponent(const ElementSpan& span, Store&& store) const {
  if (span.data == nullptr) return;
  const std::size_t size = componentSize(span.componentType);
  const auto components = static_cast<std::size_t>(span.components);
  for (std::size_t i = 0; i < span.count; ++i) {
    const std::uint8_t* element = span.data + i * span.stride;
    for (std::size_t c = 0; c < components; ++c) {
      store(i * components + c, readComponent(element + c * size, span.componentType));
    }
  }
}

template <typename Store>
void AccessorReader::applySparse(int index, const ElementSpan& span, const std::string& owner,
                                 Store&& store) const {
  const tinygltf::Accessor& accessor = accessorAt(index, owner);
  if (!accessor.sparse.isSparse) return;
  const auto& sparse = accessor.sparse;
  if (sparse.count <= 0 || static_cast<std::size_t>(sparse.count) > span.count ||
      sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
    invalid(ctx_,
            fmt::format("{}: /accessors/{}/sparse has an invalid count or offset", owner, index));
  }
  const auto count = static_cast<std::size_t>(sparse.count);
  const int indexType = sparse.indices.componentType;
  if (!formatAllowed(Semantic::Indices, indexType, false, false)) {
    invalid(ctx_, fmt::format("{}: /accessors/{}/sparse has indices of {}", owner, index,
                              componentTypeName(indexType)));
  }
  const std::size_t elementSize = componentSize(span.componentType) * span.components;
  const std::uint8_t* indices = sparseRegion(sparse.indices.bufferView, sparse.indices.byteOffset,
                                             count, componentSize(indexType), owner);
  const std::uint8_t* values =
      sparseRegion(sparse.values.bufferView, sparse.values.byteOffset, count, elementSize, owner);
  const std::size_t size = componentSize(span.componentType);
  const auto components = static_cast<std::size_t>(span.components);
  for (std::size_t i = 0; i < count; ++i) {
    const auto target =
        static_cast<std::size_t>(readComponent(indices + i * componentSize(indexType), indexType));
    if (target >= span.count) {
      invalid(ctx_, fmt::format("{}: /accessors/{}/sparse replaces element {} of {}", owner, index,
                                target, span.count));
    }
    for (std::size_t c = 0; c < components; ++c) {
      store(target * components + c,
            readComponent(values + i * elementSize + c * size, span.componentType));
    }
  }
}

const std::uint8_t* AccessorReader::sparseRegion(int view, int offset, std::size_t count,
                                                 std::size_t itemSize,
                                                 const std::string& owner) const {
  const auto [bytes, length] = bufferViewBytes(view, owner);
  const auto start = static_cast<std::size_t>(offset);
  if (start > length || count > (length - start) / itemSize) {
    invalid(ctx_,
            fmt::format("{}: sparse data reads past the end of /bufferViews/{}", owner, view));
  }
  return bytes + start;
}

}  // namespace lgh::gltf
