// Accessors: every read is bounds-checked here, not trusted to tinygltf. An accessor's format must
// be one glTF allows for what it is read as (widened by KHR_mesh_quantization), its bufferView must
// lie inside its buffer, its elements inside its bufferView, and its sparse substitutions inside
// theirs; normalised integers are decoded as glTF says.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "scene/gltf/load_context.hpp"
#include "scene/gltf/tinygltf.hpp"

namespace lgh::gltf {

// What an accessor is read as, which decides the formats glTF allows for it.
enum class Semantic {
  Position,
  Normal,
  Tangent,
  TexCoord,
  Color,
  Indices,
  MorphDelta,       // a morph target's POSITION / NORMAL / TANGENT displacement (VEC3)
  Joints,           // JOINTS_n
  Weights,          // WEIGHTS_n
  Matrix,           // inverseBindMatrices (MAT4 of FLOAT)
  AnimationInput,   // an animation sampler's times (SCALAR of FLOAT)
  AnimationOutput,  // an animation sampler's values (translation, rotation, scale, weights)
};

class AccessorReader {
 public:
  // `quantized`: the asset uses KHR_mesh_quantization.
  AccessorReader(const tinygltf::Model& model, LoadContext& ctx, bool quantized);

  // Floats, `components` per element, for a vertex attribute.
  std::vector<float> readFloats(int index, Semantic semantic, const std::string& owner,
                                int* components) const;

  std::vector<std::uint32_t> readIndices(int index, const std::string& owner) const;

  std::size_t elementCount(int index, const std::string& owner) const;

 private:
  struct ElementSpan;

  const tinygltf::Accessor& accessorAt(int index, const std::string& owner) const;

  // Bytes of bufferView `index`, after checking that it lies inside its buffer.
  std::pair<const std::uint8_t*, std::size_t> bufferViewBytes(int index,
                                                              const std::string& owner) const;

  void checkFormat(const tinygltf::Accessor& accessor, int index, Semantic semantic,
                   const std::string& owner) const;

  ElementSpan checkedSpan(int index, Semantic semantic, const std::string& owner) const;

  // An accessor without data (no bufferView) can claim any count: bound it by what the triangle
  // limit could ever use, before allocating.
  void checkCount(std::size_t count, const std::string& owner, int index) const;

  template <typename Store>
  void forEachComponent(const ElementSpan& span, Store&& store) const;

  // Sparse accessors: `count` (index, value) pairs replace elements of the dense data.
  template <typename Store>
  void applySparse(int index, const ElementSpan& span, const std::string& owner,
                   Store&& store) const;

  const std::uint8_t* sparseRegion(int view, int offset, std::size_t count, std::size_t itemSize,
                                   const std::string& owner) const;

  // NaN or Inf anywhere in the values fails the load (the validator's ACCESSOR_INVALID_FLOAT).
  void checkFinite(const std::vector<float>& values, int index, const std::string& owner,
                   int components) const;
  // Declared min/max that do not match the data, or missing on POSITION: a warning.
  void checkDeclaredBounds(const std::vector<float>& values, int index, Semantic semantic,
                           const std::string& owner, const ElementSpan& span) const;

  const tinygltf::Model& model_;
  LoadContext& ctx_;
  bool quantized_;
};

}  // namespace lgh::gltf
