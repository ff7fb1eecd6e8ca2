#include "scene/gltf/schema_check.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "lgh/error.hpp"
#include "request/json_pointer.hpp"

namespace lgh::gltf {
namespace {

using json = nlohmann::json;

namespace schema {

enum class Kind { Object, Array, String, Number, Bool, Index, Size, Count, IndexMap, Any };

struct Shape;

// Values the glTF schema allows beyond the type (the validator's VALUE_NOT_IN_RANGE): a list of
// numbers or strings, or a numeric range. Applies to the member, or to each item of an array.
struct Constraint {
  std::vector<std::int64_t> numbers = {};
  std::vector<const char*> strings = {};
  double minimum = -std::numeric_limits<double>::infinity();
  double maximum = std::numeric_limits<double>::infinity();
  bool exclusiveMinimum = false;
  std::int64_t multipleOf = 0;
};

struct Member {
  const char* name;
  Kind kind;
  bool required = false;
  const Shape* shape = nullptr;  // Object: its shape; Array: the shape of each (object) item
  Kind items = Kind::Any;        // Array: the kind of each item (when no shape)
  int length = 0;                // Array: exact length; 0: any; -1: at least one item
  const Constraint* constraint = nullptr;
};

struct Extension {
  const char* name;
  const Shape* shape;
};

struct Shape {
  std::vector<Member> members = {};
  std::vector<Extension> extensions = {};
};

Member optional(const char* name, Kind kind) { return {name, kind}; }
Member required(const char* name, Kind kind) { return {name, kind, true}; }
Member object(const char* name, const Shape& shape, bool isRequired = false) {
  return {name, Kind::Object, isRequired, &shape};
}
Member objects(const char* name, const Shape& shape, bool isRequired = false, int length = 0) {
  return {name, Kind::Array, isRequired, &shape, Kind::Any, length};
}
Member array(const char* name, Kind items, int length = 0, bool isRequired = false) {
  return {name, Kind::Array, isRequired, nullptr, items, length};
}
Member constrained(Member member, const Constraint& constraint) {
  member.constraint = &constraint;
  return member;
}

// The constraints of the glTF 2.0 schema that lghd checks.
const Constraint kComponentTypes{{5120, 5121, 5122, 5123, 5125, 5126}};
const Constraint kIndexComponentTypes{{5121, 5123, 5125}};
const Constraint kAccessorTypes{{}, {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}};
const Constraint kPrimitiveModes{{0, 1, 2, 3, 4, 5, 6}};
const Constraint kByteStride{{}, {}, 4, 252, false, 4};
const Constraint kBufferViewTargets{{34962, 34963}};
const Constraint kMagFilters{{9728, 9729}};
const Constraint kMinFilters{{9728, 9729, 9984, 9985, 9986, 9987}};
const Constraint kWraps{{33071, 33648, 10497}};
const Constraint kAlphaModes{{}, {"OPAQUE", "MASK", "BLEND"}};
const Constraint kUnitInterval{{}, {}, 0.0, 1.0};
const Constraint kNonNegative{{}, {}, 0.0};
const Constraint kPositive{{}, {}, 0.0, std::numeric_limits<double>::infinity(), true};
const Constraint kRotationComponent{{}, {}, -1.0, 1.0};
const Constraint kCameraTypes{{}, {"perspective", "orthographic"}};
const Constraint kLightTypes{{}, {"directional", "point", "spot"}};
const Constraint kInnerConeAngle{{}, {}, 0.0, 1.5707963267948966};
const Constraint kOuterConeAngle{{}, {}, 0.0, 1.5707963267948966, true};

const Shape& textureInfo() {
  static const Shape shape{{required("index", Kind::Index), optional("texCoord", Kind::Index)}};
  return shape;
}
const Shape& normalTextureInfo() {
  static const Shape shape{{required("index", Kind::Index), optional("texCoord", Kind::Index),
                            optional("scale", Kind::Number)}};
  return shape;
}
const Shape& occlusionTextureInfo() {
  static const Shape shape{{required("index", Kind::Index), optional("texCoord", Kind::Index),
                            constrained(optional("strength", Kind::Number), kUnitInterval)}};
  return shape;
}
const Shape& pbrMetallicRoughness() {
  static const Shape shape{{constrained(array("baseColorFactor", Kind::Number, 4), kUnitInterval),
                            object("baseColorTexture", textureInfo()),
                            constrained(optional("metallicFactor", Kind::Number), kUnitInterval),
                            constrained(optional("roughnessFactor", Kind::Number), kUnitInterval),
                            object("metallicRoughnessTexture", textureInfo())}};
  return shape;
}
const Shape& emissiveStrength() {
  static const Shape shape{{constrained(optional("emissiveStrength", Kind::Number), kNonNegative)}};
  return shape;
}
const Shape& material() {
  static const Shape shape{
      {object("pbrMetallicRoughness", pbrMetallicRoughness()),
       object("normalTexture", normalTextureInfo()),
       object("occlusionTexture", occlusionTextureInfo()), object("emissiveTexture", textureInfo()),
       constrained(array("emissiveFactor", Kind::Number, 3), kUnitInterval),
       constrained(optional("alphaMode", Kind::String), kAlphaModes),
       constrained(optional("alphaCutoff", Kind::Number), kNonNegative),
       optional("doubleSided", Kind::Bool)},
      {{"KHR_materials_emissive_strength", &emissiveStrength()}}};
  return shape;
}
const Shape& primitive() {
  static const Shape shape{{required("attributes", Kind::IndexMap),
                            optional("indices", Kind::Index), optional("material", Kind::Index),
                            constrained(optional("mode", Kind::Index), kPrimitiveModes),
                            array("targets", Kind::IndexMap)}};
  return shape;
}
const Shape& mesh() {
  static const Shape shape{
      {objects("primitives", primitive(), true, -1), array("weights", Kind::Number)}};
  return shape;
}
const Shape& nodeLight() {
  static const Shape shape{{required("light", Kind::Index)}};
  return shape;
}
const Shape& node() {
  static const Shape shape{{optional("camera", Kind::Index), optional("skin", Kind::Index),
                            optional("mesh", Kind::Index), array("children", Kind::Index),
                            array("matrix", Kind::Number, 16),
                            constrained(array("rotation", Kind::Number, 4), kRotationComponent),
                            array("scale", Kind::Number, 3), array("translation", Kind::Number, 3),
                            array("weights", Kind::Number)},
                           {{"KHR_lights_punctual", &nodeLight()}}};
  return shape;
}
const Shape& scene() {
  static const Shape shape{{array("nodes", Kind::Index)}};
  return shape;
}
// Sparse byteOffsets are Index, not Size: tinygltf keeps them as int, and a larger value would
// wrap around unnoticed.
const Shape& sparseIndices() {
  static const Shape shape{
      {required("bufferView", Kind::Index), optional("byteOffset", Kind::Index),
       constrained(required("componentType", Kind::Index), kIndexComponentTypes)}};
  return shape;
}
const Shape& sparseValues() {
  static const Shape shape{
      {required("bufferView", Kind::Index), optional("byteOffset", Kind::Index)}};
  return shape;
}
const Shape& sparse() {
  static const Shape shape{{required("count", Kind::Count),
                            object("indices", sparseIndices(), true),
                            object("values", sparseValues(), true)}};
  return shape;
}
const Shape& accessor() {
  static const Shape shape{{optional("bufferView", Kind::Index), optional("byteOffset", Kind::Size),
                            constrained(required("componentType", Kind::Index), kComponentTypes),
                            optional("normalized", Kind::Bool), required("count", Kind::Count),
                            constrained(required("type", Kind::String), kAccessorTypes),
                            array("max", Kind::Number), array("min", Kind::Number),
                            object("sparse", sparse())}};
  return shape;
}
const Shape& bufferView() {
  static const Shape shape{{required("buffer", Kind::Index), optional("byteOffset", Kind::Size),
                            required("byteLength", Kind::Count),
                            constrained(optional("byteStride", Kind::Size), kByteStride),
                            constrained(optional("target", Kind::Index), kBufferViewTargets)}};
  return shape;
}
const Shape& buffer() {
  static const Shape shape{{optional("uri", Kind::String), required("byteLength", Kind::Count)}};
  return shape;
}
const Shape& image() {
  static const Shape shape{{optional("uri", Kind::String), optional("mimeType", Kind::String),
                            optional("bufferView", Kind::Index)}};
  return shape;
}
const Shape& texture() {
  static const Shape shape{{optional("sampler", Kind::Index), optional("source", Kind::Index)}};
  return shape;
}
const Shape& sampler() {
  static const Shape shape{{constrained(optional("magFilter", Kind::Index), kMagFilters),
                            constrained(optional("minFilter", Kind::Index), kMinFilters),
                            constrained(optional("wrapS", Kind::Index), kWraps),
                            constrained(optional("wrapT", Kind::Index), kWraps)}};
  return shape;
}
const Shape& perspective() {
  static const Shape shape{{constrained(optional("aspectRatio", Kind::Number), kPositive),
                            constrained(required("yfov", Kind::Number), kPositive),
                            constrained(optional("zfar", Kind::Number), kPositive),
                            constrained(required("znear", Kind::Number), kPositive)}};
  return shape;
}
const Shape& orthographic() {
  static const Shape shape{{required("xmag", Kind::Number), required("ymag", Kind::Number),
                            constrained(required("zfar", Kind::Number), kPositive),
                            constrained(required("znear", Kind::Number), kNonNegative)}};
  return shape;
}
const Shape& camera() {
  static const Shape shape{{constrained(required("type", Kind::String), kCameraTypes),
                            object("perspective", perspective()),
                            object("orthographic", orthographic())}};
  return shape;
}
const Shape& skin() {
  static const Shape shape{{optional("inverseBindMatrices", Kind::Index),
                            optional("skeleton", Kind::Index),
                            array("joints", Kind::Index, -1, true)}};
  return shape;
}
const Shape& anyObject() {
  static const Shape shape{};
  return shape;
}
const Shape& spot() {
  static const Shape shape{
      {constrained(optional("innerConeAngle", Kind::Number), kInnerConeAngle),
       constrained(optional("outerConeAngle", Kind::Number), kOuterConeAngle)}};
  return shape;
}
const Shape& light() {
  static const Shape shape{{constrained(required("type", Kind::String), kLightTypes),
                            constrained(array("color", Kind::Number, 3), kUnitInterval),
                            constrained(optional("intensity", Kind::Number), kNonNegative),
                            constrained(optional("range", Kind::Number), kPositive),
                            object("spot", spot())}};
  return shape;
}
const Shape& lightsPunctual() {
  static const Shape shape{{objects("lights", light())}};
  return shape;
}
const Shape& asset() {
  static const Shape shape{{required("version", Kind::String), optional("generator", Kind::String),
                            optional("minVersion", Kind::String),
                            optional("copyright", Kind::String)}};
  return shape;
}
const Shape& root() {
  static const Shape shape{
      {object("asset", asset(), true), optional("scene", Kind::Index), objects("scenes", scene()),
       objects("nodes", node()), objects("meshes", mesh()), objects("accessors", accessor()),
       objects("bufferViews", bufferView()), objects("buffers", buffer()),
       objects("materials", material()), objects("textures", texture()), objects("images", image()),
       objects("samplers", sampler()), objects("cameras", camera()), objects("skins", skin()),
       objects("animations", anyObject()), array("extensionsUsed", Kind::String),
       array("extensionsRequired", Kind::String)},
      {{"KHR_lights_punctual", &lightsPunctual()}}};
  return shape;
}

bool isNonNegativeInteger(const json& value, std::uint64_t max, std::uint64_t min = 0) {
  if (value.is_number_unsigned()) {
    const auto number = value.get<std::uint64_t>();
    return number >= min && number <= max;
  }
  if (value.is_number_integer()) {
    const auto number = value.get<std::int64_t>();
    return number >= 0 && static_cast<std::uint64_t>(number) >= min &&
           static_cast<std::uint64_t>(number) <= max;
  }
  return false;
}

constexpr std::uint64_t kMaxSize = 1ULL << 53;  // exact in a double, as JSON numbers are

bool matches(const json& value, Kind kind) {
  switch (kind) {
    case Kind::Object:
      return value.is_object();
    case Kind::Array:
      return value.is_array();
    case Kind::String:
      return value.is_string();
    case Kind::Number:
      return value.is_number();
    case Kind::Bool:
      return value.is_boolean();
    case Kind::Index:
      return isNonNegativeInteger(value, INT_MAX);
    case Kind::Size:
      return isNonNegativeInteger(value, kMaxSize);
    case Kind::Count:
      return isNonNegativeInteger(value, kMaxSize, 1);
    case Kind::IndexMap:
      return value.is_object() && std::all_of(value.begin(), value.end(), [](const json& item) {
               return isNonNegativeInteger(item, INT_MAX);
             });
    case Kind::Any:
      return true;
  }
  return false;
}

const char* describe(Kind kind) {
  switch (kind) {
    case Kind::Object:
      return "an object";
    case Kind::Array:
      return "an array";
    case Kind::String:
      return "a string";
    case Kind::Number:
      return "a number";
    case Kind::Bool:
      return "a boolean";
    case Kind::Index:
    case Kind::Size:
      return "a non-negative integer";
    case Kind::Count:
      return "a positive integer";
    case Kind::IndexMap:
      return "an object of non-negative integers";
    case Kind::Any:
      return "anything";
  }
  return "?";
}

// JSON pointer escaping (RFC 6901) for member names taken from the document.
std::string escapePointer(const std::string& token) { return escapePointerToken(token); }

class Checker {
 public:
  explicit Checker(std::string file) : file_(std::move(file)) {}

  void checkObject(const json& value, const Shape& shape, const std::string& pointer) const {
    if (!value.is_object()) fail(pointer, "must be an object");
    // Wrongly typed members first: they say more about a broken file than a missing one does.
    for (const Member& member : shape.members) {
      const auto it = value.find(member.name);
      if (it != value.end()) checkMember(*it, member, pointer + "/" + member.name);
    }
    for (const Member& member : shape.members) {
      if (member.required && !value.contains(member.name)) {
        fail(pointer + "/" + member.name, "is required");
      }
    }
    checkCommon(value, shape, pointer);
  }

 private:
  // name, extensions and extras, which every glTF object may have.
  void checkCommon(const json& value, const Shape& shape, const std::string& pointer) const {
    if (const auto name = value.find("name"); name != value.end() && !name->is_string()) {
      fail(pointer + "/name", "must be a string");
    }
    const auto extensions = value.find("extensions");
    if (extensions == value.end()) return;
    const std::string path = pointer + "/extensions";
    if (!extensions->is_object()) fail(path, "must be an object");
    for (const auto& [key, extension] : extensions->items()) {
      const std::string extensionPath = path + "/" + escapePointer(key);
      if (!extension.is_object()) fail(extensionPath, "must be an object");
      for (const Extension& known : shape.extensions) {
        if (key == known.name) checkObject(extension, *known.shape, extensionPath);
      }
    }
  }

  void checkMember(const json& value, const Member& member, const std::string& path) const {
    if (member.kind == Kind::Object && member.shape != nullptr) {
      checkObject(value, *member.shape, path);
      return;
    }
    if (!matches(value, member.kind)) fail(path, fmt::format("must be {}", describe(member.kind)));
    if (member.kind == Kind::Array) {
      checkItems(value, member, path);
    } else if (member.constraint != nullptr) {
      checkConstraint(value, *member.constraint, path);
    }
  }

  void checkConstraint(const json& value, const Constraint& constraint,
                       const std::string& path) const {
    if (!constraint.numbers.empty()) {
      const bool listed = value.is_number_integer() &&
                          std::find(constraint.numbers.begin(), constraint.numbers.end(),
                                    value.get<std::int64_t>()) != constraint.numbers.end();
      if (!listed) {
        fail(path, fmt::format("must be one of {}, got {}", fmt::join(constraint.numbers, ", "),
                               value.dump()));
      }
    }
    if (!constraint.strings.empty()) {
      const bool listed =
          value.is_string() && std::any_of(constraint.strings.begin(), constraint.strings.end(),
                                           [&](const char* text) { return value == text; });
      if (!listed) {
        fail(path, fmt::format("must be one of {}, got {}", fmt::join(constraint.strings, ", "),
                               value.dump()));
      }
    }
    if (!value.is_number()) return;
    const double number = value.get<double>();
    const bool belowMinimum = constraint.exclusiveMinimum ? !(number > constraint.minimum)
                                                          : !(number >= constraint.minimum);
    if (belowMinimum || !(number <= constraint.maximum)) {
      fail(path, fmt::format("must be {} {}{}, got {}",
                             constraint.exclusiveMinimum ? "greater than" : "at least",
                             constraint.minimum,
                             std::isinf(constraint.maximum)
                                 ? std::string()
                                 : fmt::format(" and at most {}", constraint.maximum),
                             value.dump()));
    }
    if (constraint.multipleOf > 0 && value.get<std::int64_t>() % constraint.multipleOf != 0) {
      fail(path,
           fmt::format("must be a multiple of {}, got {}", constraint.multipleOf, value.dump()));
    }
  }

  void checkItems(const json& array, const Member& member, const std::string& path) const {
    if (member.length > 0 && array.size() != static_cast<std::size_t>(member.length)) {
      fail(path, fmt::format("must have {} items, not {}", member.length, array.size()));
    }
    if (member.length < 0 && array.empty()) fail(path, "must not be empty");
    for (std::size_t i = 0; i < array.size(); ++i) {
      const std::string itemPath = fmt::format("{}/{}", path, i);
      if (member.shape != nullptr) {
        checkObject(array[i], *member.shape, itemPath);
      } else if (!matches(array[i], member.items)) {
        fail(itemPath, fmt::format("must be {}", describe(member.items)));
      } else if (member.constraint != nullptr) {
        checkConstraint(array[i], *member.constraint, itemPath);
      }
    }
  }

  [[noreturn]] void fail(const std::string& pointer, const std::string& problem) const {
    throw Error(
        ErrorCode::Invalid,
        fmt::format("invalid glTF: {} {}", pointer.empty() ? "the document" : pointer, problem),
        file_);
  }

  std::string file_;
};

}  // namespace schema

}  // namespace

void checkSchema(const nlohmann::json& document, const std::string& displayName) {
  schema::Checker(displayName).checkObject(document, schema::root(), "");
}

}  // namespace lgh::gltf
