// tinygltf is built here and only here. It decodes no images itself (our image I/O does, through
// SetImageLoader) and has no file system access of its own (TINYGLTF_NO_FS): every side file is
// read through the sandboxed callbacks below.
// tinygltf's (unused) writer needs <fstream> but includes it only without TINYGLTF_NO_FS.
#include <fstream>

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_FS
#include <tiny_gltf.h>

#include "request/json_pointer.hpp"
#include "scene/gltf_loader.hpp"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <new>
#include <optional>
#include <set>
#include <string_view>

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "lgh/error.hpp"
#include "lgh/image.hpp"
#include "scene/asset_path.hpp"
#include "scene/tangents.hpp"

namespace lgh {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int kMaxNodeDepth = 64;
// Node visits (instances of nodes) before a hierarchy counts as a decompression bomb: a DAG that
// shares children doubles per level.
constexpr std::size_t kMaxNodeVisits = 1U << 20;

// Extensions this loader implements; a REQUIRED extension outside this set fails the load.
const std::set<std::string, std::less<>> kSupportedExtensions = {
    "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_mesh_quantization"};

// ---------------------------------------------------------------------------------------------
// Schema pre-check. tinygltf ignores members of the wrong JSON type (a "scene": "hello" or a
// "primitives" object just vanish), which turns a broken asset into a silently different one.
// This checks the members we (or tinygltf) consume against the glTF 2.0 schema's types first.

namespace schema {

enum class Kind { Object, Array, String, Number, Bool, Index, Size, Count, IndexMap, Any };

struct Shape;

struct Member {
  const char* name;
  Kind kind;
  bool required = false;
  const Shape* shape = nullptr;  // Object: its shape; Array: the shape of each (object) item
  Kind items = Kind::Any;        // Array: the kind of each item (when no shape)
  int length = 0;                // Array: exact length; 0: any; -1: at least one item
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
                            optional("strength", Kind::Number)}};
  return shape;
}
const Shape& pbrMetallicRoughness() {
  static const Shape shape{
      {array("baseColorFactor", Kind::Number, 4), object("baseColorTexture", textureInfo()),
       optional("metallicFactor", Kind::Number), optional("roughnessFactor", Kind::Number),
       object("metallicRoughnessTexture", textureInfo())}};
  return shape;
}
const Shape& emissiveStrength() {
  static const Shape shape{{optional("emissiveStrength", Kind::Number)}};
  return shape;
}
const Shape& material() {
  static const Shape shape{
      {object("pbrMetallicRoughness", pbrMetallicRoughness()),
       object("normalTexture", normalTextureInfo()),
       object("occlusionTexture", occlusionTextureInfo()), object("emissiveTexture", textureInfo()),
       array("emissiveFactor", Kind::Number, 3), optional("alphaMode", Kind::String),
       optional("alphaCutoff", Kind::Number), optional("doubleSided", Kind::Bool)},
      {{"KHR_materials_emissive_strength", &emissiveStrength()}}};
  return shape;
}
const Shape& primitive() {
  static const Shape shape{{required("attributes", Kind::IndexMap),
                            optional("indices", Kind::Index), optional("material", Kind::Index),
                            optional("mode", Kind::Index), array("targets", Kind::IndexMap)}};
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
                            array("matrix", Kind::Number, 16), array("rotation", Kind::Number, 4),
                            array("scale", Kind::Number, 3), array("translation", Kind::Number, 3),
                            array("weights", Kind::Number)},
                           {{"KHR_lights_punctual", &nodeLight()}}};
  return shape;
}
const Shape& scene() {
  static const Shape shape{{array("nodes", Kind::Index)}};
  return shape;
}
const Shape& sparseIndices() {
  static const Shape shape{{required("bufferView", Kind::Index), optional("byteOffset", Kind::Size),
                            required("componentType", Kind::Index)}};
  return shape;
}
const Shape& sparseValues() {
  static const Shape shape{
      {required("bufferView", Kind::Index), optional("byteOffset", Kind::Size)}};
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
                            required("componentType", Kind::Index),
                            optional("normalized", Kind::Bool), required("count", Kind::Count),
                            required("type", Kind::String), array("max", Kind::Number),
                            array("min", Kind::Number), object("sparse", sparse())}};
  return shape;
}
const Shape& bufferView() {
  static const Shape shape{{required("buffer", Kind::Index), optional("byteOffset", Kind::Size),
                            required("byteLength", Kind::Count), optional("byteStride", Kind::Size),
                            optional("target", Kind::Index)}};
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
  static const Shape shape{{optional("magFilter", Kind::Index), optional("minFilter", Kind::Index),
                            optional("wrapS", Kind::Index), optional("wrapT", Kind::Index)}};
  return shape;
}
const Shape& perspective() {
  static const Shape shape{{optional("aspectRatio", Kind::Number), required("yfov", Kind::Number),
                            optional("zfar", Kind::Number), required("znear", Kind::Number)}};
  return shape;
}
const Shape& orthographic() {
  static const Shape shape{{required("xmag", Kind::Number), required("ymag", Kind::Number),
                            required("zfar", Kind::Number), required("znear", Kind::Number)}};
  return shape;
}
const Shape& camera() {
  static const Shape shape{{required("type", Kind::String), object("perspective", perspective()),
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
      {optional("innerConeAngle", Kind::Number), optional("outerConeAngle", Kind::Number)}};
  return shape;
}
const Shape& light() {
  static const Shape shape{{required("type", Kind::String), array("color", Kind::Number, 3),
                            optional("intensity", Kind::Number), optional("range", Kind::Number),
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
    if (member.kind == Kind::Array) checkItems(value, member, path);
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

// "mesh 3 ('Teapot')", or "mesh 3" when unnamed: how messages name glTF objects.
std::string label(const char* kind, int index, const std::string& name) {
  return name.empty() ? fmt::format("{} {}", kind, index)
                      : fmt::format("{} {} ('{}')", kind, index, name);
}

// ---------------------------------------------------------------------------------------------
// Load context: what the tinygltf callbacks need, and what they found.

// Where a model's side files (buffers and images referenced by URI) come from.
enum class SideFiles { Directory, Memory, None };

struct LoadContext {
  std::string displayName;
  SceneLoadLimits limits;
  SideFiles sideFiles = SideFiles::None;
  fs::path root;     // Directory: the asset root
  fs::path baseDir;  // Directory, Memory: the model's folder, relative (to root / to the upload)
  std::map<std::string, const std::vector<std::uint8_t>*> memoryFiles;  // normalised name
  std::optional<Error> fatal;               // a sandbox violation: always fails the load
  std::map<std::string, Error> fileErrors;  // missing / too large side files, by URI
  std::map<int, Image8> images;             // decoded, by glTF image index
  std::map<int, Error> imageErrors;         // decode failures, by glTF image index
  std::vector<std::string> warnings;

  void warnOnce(const std::string& warning) {
    if (std::find(warnings.begin(), warnings.end(), warning) == warnings.end()) {
      warnings.push_back(warning);
    }
  }
};

[[noreturn]] void invalid(const LoadContext& ctx, const std::string& message) {
  throw Error(ErrorCode::Invalid, message, ctx.displayName);
}

[[noreturn]] void tooLarge(const LoadContext& ctx, const std::string& message) {
  throw Error(ErrorCode::TooLarge, message, ctx.displayName);
}

// A URI key independent of spelling ("./a.bin" and "a.bin" are one file).
std::string uriKey(const std::string& uri) {
  try {
    return checkRelativeAssetPath(uri, "").generic_string();
  } catch (const Error&) {
    return uri;
  }
}

// "scheme:..." (http:, file:, ...): not a relative reference. data: URIs never get here.
bool hasUriScheme(const std::string& uri) {
  const auto colon = uri.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  return std::all_of(uri.begin(), uri.begin() + static_cast<std::ptrdiff_t>(colon), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
  });
}

struct SideFile {
  fs::path path;                                     // Directory
  const std::vector<std::uint8_t>* bytes = nullptr;  // Memory
};

// Resolves a (percent-decoded) URI of the model to a file: on disk inside the asset root, or in
// the uploaded files. Throws lgh::Error: Invalid for a sandbox violation, NotFound.
SideFile locateSideFile(const LoadContext& ctx, const std::string& uri) {
  if (ctx.sideFiles == SideFiles::None) {
    invalid(ctx, fmt::format("an inline .glb cannot reference the external file '{}'; embed it "
                             "(GLB buffer, bufferView image or data: URI)",
                             uri));
  }
  if (hasUriScheme(uri)) {
    invalid(ctx,
            fmt::format("URI '{}' is not supported: only relative file paths and data: URIs", uri));
  }
  fs::path relative;
  try {
    relative = checkRelativeAssetPath(uri, ctx.displayName);
  } catch (const Error& error) {
    invalid(ctx, fmt::format("URI rejected by the asset sandbox: {}", error.message()));
  }
  const std::string inModel = (ctx.baseDir / relative).lexically_normal().generic_string();
  if (ctx.sideFiles == SideFiles::Memory) {
    const auto it = ctx.memoryFiles.find(inModel);
    if (it == ctx.memoryFiles.end()) {
      throw Error(ErrorCode::NotFound,
                  fmt::format("file '{}' referenced by the asset was not uploaded", uri),
                  ctx.displayName);
    }
    return {{}, it->second};
  }
  try {
    return {resolveAssetPath(ctx.root, inModel, ctx.displayName)};
  } catch (const Error& error) {
    if (error.code() == ErrorCode::NotFound) {
      throw Error(ErrorCode::NotFound,
                  fmt::format("file '{}' referenced by the asset not found", uri), ctx.displayName);
    }
    invalid(ctx, fmt::format("URI rejected by the asset sandbox: {}", error.message()));
  }
}

// Missing and oversized files are per file (an unused image may be missing); anything else is a
// sandbox violation and fails the load however tinygltf goes on.
void recordFileError(LoadContext& ctx, const std::string& uri, const Error& error) {
  if (error.code() == ErrorCode::NotFound || error.code() == ErrorCode::TooLarge) {
    ctx.fileErrors.emplace(uriKey(uri), error);
  } else if (!ctx.fatal) {
    ctx.fatal = error;
  }
}

std::vector<std::uint8_t> readSideFile(const LoadContext& ctx, const std::string& uri,
                                       const SideFile& file) {
  const std::size_t size = file.bytes != nullptr
                               ? file.bytes->size()
                               : static_cast<std::size_t>(fs::file_size(file.path));
  if (size > ctx.limits.maxFileBytes) {
    tooLarge(ctx, fmt::format("file '{}' is {} bytes, over the limit of {}", uri, size,
                              ctx.limits.maxFileBytes));
  }
  if (file.bytes != nullptr) return *file.bytes;
  std::vector<std::uint8_t> bytes(size);
  std::ifstream stream(file.path, std::ios::binary);
  if (!stream.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) {
    throw Error(ErrorCode::NotFound, fmt::format("file '{}' could not be read", uri),
                ctx.displayName);
  }
  return bytes;
}

// tinygltf FsCallbacks. tinygltf hands over JoinPath(base_dir, uri) with the URI percent-decoded;
// we pass an empty base_dir, so the path is the decoded URI itself (its retry is "./" + URI).
bool fileExistsCallback(const std::string& path, void* user) {
  auto& ctx = *static_cast<LoadContext*>(user);
  try {
    locateSideFile(ctx, path);
    return true;
  } catch (const Error& error) {
    recordFileError(ctx, path, error);
    return false;
  }
}

std::string expandFilePathCallback(const std::string& path, void*) { return path; }

bool readWholeFileCallback(std::vector<unsigned char>* out, std::string* err,
                           const std::string& path, void* user) {
  auto& ctx = *static_cast<LoadContext*>(user);
  try {
    *out = readSideFile(ctx, path, locateSideFile(ctx, path));
    return true;
  } catch (const Error& error) {
    recordFileError(ctx, path, error);
    if (err != nullptr) *err += error.message();
    return false;
  } catch (const std::exception& error) {  // file_size races, bad_alloc
    recordFileError(ctx, path, Error(ErrorCode::NotFound, error.what(), ctx.displayName));
    if (err != nullptr) *err += error.what();
    return false;
  }
}

bool writeWholeFileCallback(std::string* err, const std::string&, const std::vector<unsigned char>&,
                            void*) {
  if (err != nullptr) *err += "the loader writes no files";
  return false;
}

// ---------------------------------------------------------------------------------------------
// Images.

std::uint32_t readBigEndian(const std::uint8_t* bytes, int count) {
  std::uint32_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8U) | bytes[i];
  return value;
}

// JPEG frame size from the first SOFn marker, without decoding.
std::optional<std::pair<std::uint32_t, std::uint32_t>> jpegSize(const std::uint8_t* bytes,
                                                                std::size_t size) {
  std::size_t i = 2;
  while (i + 4 <= size) {
    if (bytes[i] != 0xFF) return std::nullopt;
    const std::uint8_t marker = bytes[i + 1];
    if (marker == 0xFF) {  // fill byte
      ++i;
      continue;
    }
    i += 2;
    const bool standalone = marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8);
    if (standalone) continue;
    if (marker == 0xD9 || marker == 0xDA) return std::nullopt;  // no frame header before scan
    const std::uint32_t length = readBigEndian(bytes + i, 2);
    const bool frame =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (frame) {
      if (i + 7 > size) return std::nullopt;
      return std::make_pair(readBigEndian(bytes + i + 5, 2), readBigEndian(bytes + i + 3, 2));
    }
    if (length < 2) return std::nullopt;
    i += length;
  }
  return std::nullopt;
}

// Width and height from a PNG or JPEG header, so that an oversized texture is refused before
// the decoder allocates for it (a small file can claim 65535 x 65535 pixels).
std::optional<std::pair<std::uint32_t, std::uint32_t>> sniffImageSize(const std::uint8_t* bytes,
                                                                      std::size_t size) {
  static constexpr std::uint8_t kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (size >= 24 && std::memcmp(bytes, kPng, 8) == 0 && std::memcmp(bytes + 12, "IHDR", 4) == 0) {
    return std::make_pair(readBigEndian(bytes + 16, 4), readBigEndian(bytes + 20, 4));
  }
  if (size >= 4 && bytes[0] == 0xFF && bytes[1] == 0xD8) return jpegSize(bytes, size);
  return std::nullopt;
}

void checkTextureSize(const LoadContext& ctx, std::uint64_t width, std::uint64_t height,
                      const std::string& what) {
  const auto limit = static_cast<std::uint64_t>(std::max(ctx.limits.maxTextureSize, 0));
  if (width > limit || height > limit) {
    tooLarge(ctx,
             fmt::format("{} is {} x {} pixels, over the limit of {}", what, width, height, limit));
  }
}

Image8 decodeTexture(const LoadContext& ctx, const std::uint8_t* bytes, std::size_t size,
                     const std::string& what) {
  if (bytes == nullptr || size == 0) invalid(ctx, fmt::format("{} has no data", what));
  if (const auto header = sniffImageSize(bytes, size)) {
    checkTextureSize(ctx, header->first, header->second, what);
  }
  Image8 image;
  try {
    image = image_io::decodeTextureRgba8(bytes, size, what);
  } catch (const Error& error) {
    if (error.code() == ErrorCode::TooLarge) throw;
    invalid(ctx, fmt::format("{} could not be decoded: {}", what, error.message()));
  }
  checkTextureSize(ctx, static_cast<std::uint64_t>(std::max(image.width, 0)),
                   static_cast<std::uint64_t>(std::max(image.height, 0)), what);
  const auto expected = static_cast<std::size_t>(image.width) * image.height * 4;
  if (image.width <= 0 || image.height <= 0 || image.channels != 4 ||
      image.pixels.size() != expected) {
    invalid(ctx, fmt::format("{} decoded to an unusable image", what));
  }
  return image;
}

std::string imageLabel(const tinygltf::Image& image, int index) {
  std::string text = label("image", index, image.name);
  if (!image.uri.empty()) text += fmt::format(" '{}'", image.uri);
  return text;
}

// tinygltf LoadImageDataFunction. Never fails the parse: an image that cannot be decoded only
// matters if a material uses it (checked when textures are resolved).
bool loadImageCallback(tinygltf::Image* image, const int index, std::string*, std::string*, int,
                       int, const unsigned char* bytes, int size, void* user) {
  auto& ctx = *static_cast<LoadContext*>(user);
  const std::string what = imageLabel(*image, index);
  try {
    if (size <= 0) invalid(ctx, fmt::format("{} has no data", what));
    Image8 decoded = decodeTexture(ctx, bytes, static_cast<std::size_t>(size), what);
    image->width = decoded.width;
    image->height = decoded.height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    ctx.images.insert_or_assign(index, std::move(decoded));
  } catch (const Error& error) {
    ctx.imageErrors.insert_or_assign(index, error);
  } catch (const std::bad_alloc&) {
    ctx.imageErrors.insert_or_assign(
        index, Error(ErrorCode::TooLarge, what + " is too large to decode", ctx.displayName));
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Accessors: every read is bounds-checked here, not trusted to tinygltf.

enum class Semantic { Position, Normal, Tangent, TexCoord, Color, Indices };

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
      return type == TINYGLTF_TYPE_SCALAR;
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

// Element data of one accessor after every check: element i starts at data + i * stride.
struct ElementSpan {
  const std::uint8_t* data = nullptr;  // nullptr: no bufferView, all zeros (glTF's rule)
  std::size_t stride = 0;
  std::size_t count = 0;
  int components = 0;
  int componentType = 0;
  bool normalized = false;
};

class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& model, LoadContext& ctx, bool quantized)
      : model_(model), ctx_(ctx), quantized_(quantized) {}

  // Floats, `components` per element, for a vertex attribute.
  std::vector<float> readFloats(int index, Semantic semantic, const std::string& owner,
                                int* components) const {
    const ElementSpan span = checkedSpan(index, semantic, owner);
    std::vector<float> values(span.count * static_cast<std::size_t>(span.components), 0.0F);
    forEachComponent(span, [&](std::size_t slot, double value) {
      values[slot] = toFloat(value, span.componentType, span.normalized);
    });
    applySparse(index, span, owner, [&](std::size_t slot, double value) {
      values[slot] = toFloat(value, span.componentType, span.normalized);
    });
    *components = span.components;
    return values;
  }

  std::vector<std::uint32_t> readIndices(int index, const std::string& owner) const {
    const ElementSpan span = checkedSpan(index, Semantic::Indices, owner);
    std::vector<std::uint32_t> values(span.count, 0);
    auto store = [&](std::size_t slot, double value) {
      values[slot] = static_cast<std::uint32_t>(value);
    };
    forEachComponent(span, store);
    applySparse(index, span, owner, store);
    return values;
  }

  std::size_t elementCount(int index, const std::string& owner) const {
    return accessorAt(index, owner).count;
  }

 private:
  const tinygltf::Accessor& accessorAt(int index, const std::string& owner) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size()) {
      invalid(ctx_, fmt::format("{}: accessor {} does not exist", owner, index));
    }
    return model_.accessors[static_cast<std::size_t>(index)];
  }

  // Bytes of bufferView `index`, after checking that it lies inside its buffer.
  std::pair<const std::uint8_t*, std::size_t> bufferViewBytes(int index,
                                                              const std::string& owner) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.bufferViews.size()) {
      invalid(ctx_, fmt::format("{}: bufferView {} does not exist", owner, index));
    }
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(index)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size()) {
      invalid(ctx_, fmt::format("{}: bufferView {} names buffer {}, which does not exist", owner,
                                index, view.buffer));
    }
    const std::vector<unsigned char>& data =
        model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
      invalid(ctx_, fmt::format("{}: bufferView {} (offset {}, length {}) lies outside buffer {} "
                                "({} bytes)",
                                owner, index, view.byteOffset, view.byteLength, view.buffer,
                                data.size()));
    }
    return {data.data() + view.byteOffset, view.byteLength};
  }

  void checkFormat(const tinygltf::Accessor& accessor, int index, Semantic semantic,
                   const std::string& owner) const {
    if (typeAllowed(semantic, accessor.type) &&
        formatAllowed(semantic, accessor.componentType, accessor.normalized, quantized_)) {
      return;
    }
    invalid(ctx_, fmt::format("{}: accessor {} is {} of {}{}; glTF requires {}", owner, index,
                              typeName(accessor.type), accessor.normalized ? "normalized " : "",
                              componentTypeName(accessor.componentType), allowedFormats(semantic)));
  }

  ElementSpan checkedSpan(int index, Semantic semantic, const std::string& owner) const {
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
      invalid(ctx_, fmt::format("{}: accessor {} has byteStride {} smaller than its {}-byte "
                                "elements",
                                owner, index, span.stride, elementSize));
    }
    // offset + stride * (count - 1) + elementSize <= length, without overflow.
    const bool fits = accessor.byteOffset <= length &&
                      elementSize <= length - accessor.byteOffset &&
                      span.count - 1 <= (length - accessor.byteOffset - elementSize) / span.stride;
    if (!fits) {
      invalid(ctx_, fmt::format("{}: accessor {} ({} elements of {} bytes, stride {}, offset {}) "
                                "reads past the end of bufferView {} ({} bytes)",
                                owner, index, span.count, elementSize, span.stride,
                                accessor.byteOffset, accessor.bufferView, length));
    }
    span.data = bytes + accessor.byteOffset;
    return span;
  }

  // An accessor without data (no bufferView) can claim any count: bound it by what the triangle
  // limit could ever use, before allocating.
  void checkCount(std::size_t count, const std::string& owner, int index) const {
    const std::size_t maxTriangles = ctx_.limits.maxTriangles;
    const std::size_t limit = maxTriangles < SIZE_MAX / 4 ? 3 * maxTriangles + 3 : SIZE_MAX;
    if (count > limit) {
      tooLarge(ctx_, fmt::format("{}: accessor {} has {} elements, more than the triangle limit "
                                 "allows ({})",
                                 owner, index, count, limit));
    }
  }

  template <typename Store>
  void forEachComponent(const ElementSpan& span, Store&& store) const {
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

  // Sparse accessors: `count` (index, value) pairs replace elements of the dense data.
  template <typename Store>
  void applySparse(int index, const ElementSpan& span, const std::string& owner,
                   Store&& store) const {
    const tinygltf::Accessor& accessor = accessorAt(index, owner);
    if (!accessor.sparse.isSparse) return;
    const auto& sparse = accessor.sparse;
    if (sparse.count <= 0 || static_cast<std::size_t>(sparse.count) > span.count ||
        sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
      invalid(ctx_,
              fmt::format("{}: sparse accessor {} has an invalid count or offset", owner, index));
    }
    const auto count = static_cast<std::size_t>(sparse.count);
    const int indexType = sparse.indices.componentType;
    if (!formatAllowed(Semantic::Indices, indexType, false, false)) {
      invalid(ctx_, fmt::format("{}: sparse accessor {} has indices of {}", owner, index,
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
      const auto target = static_cast<std::size_t>(
          readComponent(indices + i * componentSize(indexType), indexType));
      if (target >= span.count) {
        invalid(ctx_, fmt::format("{}: sparse accessor {} replaces element {} of {}", owner, index,
                                  target, span.count));
      }
      for (std::size_t c = 0; c < components; ++c) {
        store(target * components + c,
              readComponent(values + i * elementSize + c * size, span.componentType));
      }
    }
  }

  const std::uint8_t* sparseRegion(int view, int offset, std::size_t count, std::size_t itemSize,
                                   const std::string& owner) const {
    const auto [bytes, length] = bufferViewBytes(view, owner);
    const auto start = static_cast<std::size_t>(offset);
    if (start > length || count > (length - start) / itemSize) {
      invalid(ctx_,
              fmt::format("{}: sparse data reads past the end of bufferView {}", owner, view));
    }
    return bytes + start;
  }

  const tinygltf::Model& model_;
  LoadContext& ctx_;
  bool quantized_;
};

// ---------------------------------------------------------------------------------------------
// Primitives.

// Triangle lists from glTF's modes; winding as the spec's formulas.
std::vector<std::uint32_t> toTriangleList(std::vector<std::uint32_t> indices, int mode) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return indices;
  std::vector<std::uint32_t> list;
  if (indices.size() < 3) return list;
  list.reserve((indices.size() - 2) * 3);
  for (std::size_t i = 0; i + 2 < indices.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      const std::size_t odd = i % 2;
      list.insert(list.end(), {indices[i], indices[i + 1 + odd], indices[i + 2 - odd]});
    } else {  // TRIANGLE_FAN
      list.insert(list.end(), {indices[i + 1], indices[i + 2], indices[0]});
    }
  }
  return list;
}

std::size_t triangleCountFor(std::size_t indexCount, int mode) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return indexCount / 3;
  return indexCount >= 3 ? indexCount - 2 : 0;
}

const char* modeName(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "POINTS";
    case TINYGLTF_MODE_LINE:
      return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
      return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP:
      return "LINE_STRIP";
    default:
      return "an unknown mode";
  }
}

bool isTriangleMode(int mode) {
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
         mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

bool isFinite(const glm::vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

class PrimitiveConverter {
 public:
  PrimitiveConverter(const tinygltf::Model& model, LoadContext& ctx, const AccessorReader& reader)
      : model_(model), ctx_(ctx), reader_(reader) {}

  // nullopt: skipped (not triangles, or no triangles), with a warning where that loses content.
  // `trianglesSoFar` counts towards limits.maxTriangles.
  std::optional<Primitive> convert(int meshIndex, int primitiveIndex,
                                   std::size_t trianglesSoFar) const {
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(meshIndex)];
    const tinygltf::Primitive& source = mesh.primitives[static_cast<std::size_t>(primitiveIndex)];
    const std::string owner =
        fmt::format("{} primitive {}", label("mesh", meshIndex, mesh.name), primitiveIndex);
    if (!isTriangleMode(source.mode)) {
      ctx_.warnings.push_back(fmt::format("{}: mode {} ({}) is not rendered; skipped", owner,
                                          source.mode, modeName(source.mode)));
      return std::nullopt;
    }
    if (!source.targets.empty()) {
      ctx_.warnOnce("morph targets are not supported; the base meshes are rendered");
    }
    Primitive primitive;
    primitive.material = checkedMaterial(source.material, owner);
    readPositions(source, owner, primitive);
    readIndices(source, owner, trianglesSoFar, primitive);
    if (primitive.indices.empty()) return std::nullopt;
    readAttributes(source, owner, primitive);
    return primitive;
  }

 private:
  int checkedMaterial(int material, const std::string& owner) const {
    if (material >= 0 && static_cast<std::size_t>(material) >= model_.materials.size()) {
      invalid(ctx_, fmt::format("{}: material {} does not exist", owner, material));
    }
    return material;
  }

  int attributeAccessor(const tinygltf::Primitive& source, const char* name) const {
    const auto it = source.attributes.find(name);
    return it == source.attributes.end() ? -1 : it->second;
  }

  // Reads attribute `name` (count checked against the vertex count); empty when absent.
  std::vector<float> readAttribute(const tinygltf::Primitive& source, const char* name,
                                   Semantic semantic, const std::string& owner,
                                   std::size_t vertexCount, int* components) const {
    const int accessor = attributeAccessor(source, name);
    if (accessor < 0) return {};
    const std::string what = fmt::format("{} attribute {}", owner, name);
    std::vector<float> values = reader_.readFloats(accessor, semantic, what, components);
    if (values.size() != vertexCount * static_cast<std::size_t>(*components)) {
      invalid(ctx_,
              fmt::format("{}: accessor {} has {} elements but POSITION has {}", what, accessor,
                          values.size() / static_cast<std::size_t>(*components), vertexCount));
    }
    return values;
  }

  void readPositions(const tinygltf::Primitive& source, const std::string& owner,
                     Primitive& primitive) const {
    const int accessor = attributeAccessor(source, "POSITION");
    if (accessor < 0) invalid(ctx_, fmt::format("{} has no POSITION attribute", owner));
    int components = 0;
    const std::string what = fmt::format("{} attribute POSITION", owner);
    const std::vector<float> values =
        reader_.readFloats(accessor, Semantic::Position, what, &components);
    primitive.vertices.resize(values.size() / 3);
    for (std::size_t i = 0; i < primitive.vertices.size(); ++i) {
      const glm::vec3 position(values[i * 3], values[i * 3 + 1], values[i * 3 + 2]);
      if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z)) {
        invalid(ctx_, fmt::format("{}: accessor {} holds a non-finite position (NaN or Inf) at "
                                  "vertex {}",
                                  what, accessor, i));
      }
      primitive.vertices[i].position = position;
    }
  }

  void readIndices(const tinygltf::Primitive& source, const std::string& owner,
                   std::size_t trianglesSoFar, Primitive& primitive) const {
    const std::size_t vertexCount = primitive.vertices.size();
    const std::string what = fmt::format("{} indices", owner);
    const std::size_t indexCount =
        source.indices >= 0 ? reader_.elementCount(source.indices, what) : vertexCount;
    checkTriangleBudget(trianglesSoFar + triangleCountFor(indexCount, source.mode), owner);
    std::vector<std::uint32_t> indices;
    if (source.indices >= 0) {
      indices = reader_.readIndices(source.indices, what);
      checkIndexRange(indices, vertexCount, what, source.indices);
    } else {
      indices.resize(vertexCount);
      for (std::size_t i = 0; i < vertexCount; ++i) indices[i] = static_cast<std::uint32_t>(i);
    }
    primitive.indices = toTriangleList(std::move(indices), source.mode);
    if (primitive.indices.size() % 3 != 0) {
      ctx_.warnings.push_back(
          fmt::format("{}: {} indices are not a whole number of triangles; "
                      "the last {} dropped",
                      owner, primitive.indices.size(), primitive.indices.size() % 3));
      primitive.indices.resize(primitive.indices.size() - primitive.indices.size() % 3);
    }
  }

  void checkIndexRange(const std::vector<std::uint32_t>& indices, std::size_t vertexCount,
                       const std::string& what, int accessor) const {
    for (std::size_t i = 0; i < indices.size(); ++i) {
      if (indices[i] >= vertexCount) {
        invalid(ctx_, fmt::format("{}: accessor {} has index {} at position {}, out of range for "
                                  "{} vertices",
                                  what, accessor, indices[i], i, vertexCount));
      }
    }
  }

  void checkTriangleBudget(std::size_t triangles, const std::string& owner) const {
    if (triangles > ctx_.limits.maxTriangles) {
      tooLarge(ctx_, fmt::format("the asset has more than {} triangles (reached at {})",
                                 ctx_.limits.maxTriangles, owner));
    }
  }

  void readAttributes(const tinygltf::Primitive& source, const std::string& owner,
                      Primitive& primitive) const {
    const std::size_t count = primitive.vertices.size();
    int components = 0;
    const auto normals =
        readAttribute(source, "NORMAL", Semantic::Normal, owner, count, &components);
    const auto tangents =
        readAttribute(source, "TANGENT", Semantic::Tangent, owner, count, &components);
    const auto uv0 =
        readAttribute(source, "TEXCOORD_0", Semantic::TexCoord, owner, count, &components);
    const auto uv1 =
        readAttribute(source, "TEXCOORD_1", Semantic::TexCoord, owner, count, &components);
    int colorComponents = 4;
    const auto colors =
        readAttribute(source, "COLOR_0", Semantic::Color, owner, count, &colorComponents);
    std::size_t nonFinite = 0;
    for (std::size_t i = 0; i < count; ++i) {
      Vertex& v = primitive.vertices[i];
      if (!normals.empty()) v.normal = {normals[i * 3], normals[i * 3 + 1], normals[i * 3 + 2]};
      if (!tangents.empty()) {
        v.tangent = {tangents[i * 4], tangents[i * 4 + 1], tangents[i * 4 + 2],
                     tangents[i * 4 + 3]};
      }
      if (!uv0.empty()) v.uv0 = sanitized(glm::vec2(uv0[i * 2], uv0[i * 2 + 1]), 0.0F, nonFinite);
      if (!uv1.empty()) v.uv1 = sanitized(glm::vec2(uv1[i * 2], uv1[i * 2 + 1]), 0.0F, nonFinite);
      if (!colors.empty()) v.color = readColor(colors, i, colorComponents, nonFinite);
    }
    if (nonFinite > 0) {
      ctx_.warnings.push_back(
          fmt::format("{}: {} non-finite texture coordinate or colour values "
                      "replaced",
                      owner, nonFinite));
    }
    finishNormals(primitive, !normals.empty(), owner);
    finishTangents(primitive, !tangents.empty(), tangentUvSet(primitive.material), owner);
  }

  template <typename Vec>
  static Vec sanitized(Vec value, float replacement, std::size_t& replaced) {
    for (int c = 0; c < Vec::length(); ++c) {
      if (!std::isfinite(value[c])) {
        value[c] = replacement;
        ++replaced;
      }
    }
    return value;
  }

  static glm::vec4 readColor(const std::vector<float>& colors, std::size_t i, int components,
                             std::size_t& replaced) {
    const std::size_t base = i * static_cast<std::size_t>(components);
    glm::vec4 color(colors[base], colors[base + 1], colors[base + 2], 1.0F);
    if (components == 4) color.w = colors[base + 3];
    return sanitized(color, 1.0F, replaced);
  }

  void finishNormals(Primitive& primitive, bool hasNormals, const std::string& owner) const {
    if (!hasNormals) {
      generateFlatNormals(primitive);  // glTF: "client implementations MUST calculate flat normals"
      return;
    }
    if (const std::size_t repaired = repairNormals(primitive); repaired > 0) {
      ctx_.warnings.push_back(
          fmt::format("{}: {} zero-length or non-finite normals replaced by "
                      "smooth normals",
                      owner, repaired));
    }
  }

  // The UV set the material's normal map uses (tangents serve normal mapping); 0 otherwise.
  int tangentUvSet(int material) const {
    if (material < 0) return 0;
    const int texCoord =
        model_.materials[static_cast<std::size_t>(material)].normalTexture.texCoord;
    return texCoord == 1 ? 1 : 0;
  }

  void finishTangents(Primitive& primitive, bool hasTangents, int uvSet,
                      const std::string& owner) const {
    if (hasTangents && normalizeGivenTangents(primitive)) return;
    if (hasTangents) {
      ctx_.warnings.push_back(
          fmt::format("{}: TANGENT has zero, non-finite or non-unit-w values; regenerated", owner));
    }
    generateTangents(primitive, uvSet);
  }

  // Normalises the asset's tangents in place; false when any is unusable (then all are rebuilt).
  static bool normalizeGivenTangents(Primitive& primitive) {
    for (Vertex& vertex : primitive.vertices) {
      const glm::vec3 t(vertex.tangent);
      if (!isFinite(vertex.tangent) || !isUsableDirection(t)) return false;
      if (std::abs(std::abs(vertex.tangent.w) - 1.0F) > 0.01F) return false;
      vertex.tangent = glm::vec4(glm::normalize(t), vertex.tangent.w < 0.0F ? -1.0F : 1.0F);
    }
    return true;
  }

  const tinygltf::Model& model_;
  LoadContext& ctx_;
  const AccessorReader& reader_;
};

// ---------------------------------------------------------------------------------------------
// Materials and textures.

float finiteOr(double value, float fallback) {
  return std::isfinite(value) ? static_cast<float>(value) : fallback;
}

bool knownFilter(int filter, bool minification) {
  switch (filter) {
    case TINYGLTF_TEXTURE_FILTER_NEAREST:
    case TINYGLTF_TEXTURE_FILTER_LINEAR:
      return true;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR:
      return minification;
    default:
      return false;
  }
}

bool knownWrap(int wrap) {
  return wrap == TINYGLTF_TEXTURE_WRAP_REPEAT || wrap == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ||
         wrap == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
}

class MaterialConverter {
 public:
  MaterialConverter(const tinygltf::Model& model, LoadContext& ctx, Scene& scene)
      : model_(model), ctx_(ctx), scene_(scene) {}

  Material convert(int index) {
    const tinygltf::Material& source = model_.materials[static_cast<std::size_t>(index)];
    const std::string owner = label("material", index, source.name);
    Material material;
    material.name = source.name;
    const auto& pbr = source.pbrMetallicRoughness;
    for (int c = 0; c < 4 && c < static_cast<int>(pbr.baseColorFactor.size()); ++c) {
      material.baseColorFactor[c] = std::clamp(finiteOr(pbr.baseColorFactor[c], 1.0F), 0.0F, 1.0F);
    }
    material.metallicFactor = std::clamp(finiteOr(pbr.metallicFactor, 1.0F), 0.0F, 1.0F);
    material.roughnessFactor = std::clamp(finiteOr(pbr.roughnessFactor, 1.0F), 0.0F, 1.0F);
    material.emissiveFactor = emissive(source);
    material.normalScale = finiteOr(source.normalTexture.scale, 1.0F);
    material.occlusionStrength =
        std::clamp(finiteOr(source.occlusionTexture.strength, 1.0F), 0.0F, 1.0F);
    material.alphaMode = alphaMode(source.alphaMode, owner);
    material.alphaCutoff = std::max(finiteOr(source.alphaCutoff, 0.5F), 0.0F);
    material.doubleSided = source.doubleSided;
    material.baseColorTexture = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                        owner + " baseColorTexture");
    material.metallicRoughnessTexture =
        texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                owner + " metallicRoughnessTexture");
    material.normalTexture = texture(source.normalTexture.index, source.normalTexture.texCoord,
                                     owner + " normalTexture");
    material.occlusionTexture =
        texture(source.occlusionTexture.index, source.occlusionTexture.texCoord,
                owner + " occlusionTexture");
    material.emissiveTexture = texture(source.emissiveTexture.index,
                                       source.emissiveTexture.texCoord, owner + " emissiveTexture");
    return material;
  }

  // Images that failed to load but that no material used: dropped, with a warning.
  void warnAboutUnusedFailures() {
    for (const auto& [index, error] : ctx_.imageErrors) {
      if (imageRemap_.count(index) == 0) {
        ctx_.warnings.push_back(fmt::format("unused image skipped: {}", error.message()));
      }
    }
  }

 private:
  // emissiveFactor, times KHR_materials_emissive_strength's emissiveStrength when present.
  glm::vec3 emissive(const tinygltf::Material& source) const {
    glm::vec3 factor(0.0F);
    for (int c = 0; c < 3 && c < static_cast<int>(source.emissiveFactor.size()); ++c) {
      factor[c] = std::max(finiteOr(source.emissiveFactor[c], 0.0F), 0.0F);
    }
    const auto it = source.extensions.find("KHR_materials_emissive_strength");
    if (it != source.extensions.end() && it->second.Has("emissiveStrength")) {
      const tinygltf::Value& strength = it->second.Get("emissiveStrength");
      if (strength.IsNumber()) {
        factor *= std::max(finiteOr(strength.GetNumberAsDouble(), 1.0F), 0.0F);
      }
    }
    return factor;
  }

  AlphaMode alphaMode(const std::string& mode, const std::string& owner) const {
    if (mode == "OPAQUE") return AlphaMode::Opaque;
    if (mode == "MASK") return AlphaMode::Mask;
    if (mode == "BLEND") return AlphaMode::Blend;
    ctx_.warnings.push_back(fmt::format("{}: unknown alphaMode '{}', OPAQUE used", owner, mode));
    return AlphaMode::Opaque;
  }

  TextureRef texture(int textureIndex, int texCoord, const std::string& owner) {
    if (textureIndex < 0) return {};
    if (static_cast<std::size_t>(textureIndex) >= model_.textures.size()) {
      invalid(ctx_, fmt::format("{}: texture {} does not exist", owner, textureIndex));
    }
    const tinygltf::Texture& source = model_.textures[static_cast<std::size_t>(textureIndex)];
    if (source.source < 0) {
      ctx_.warnings.push_back(
          fmt::format("{}: texture {} has no image in a supported format; "
                      "ignored",
                      owner, textureIndex));
      return {};
    }
    if (static_cast<std::size_t>(source.source) >= model_.images.size()) {
      invalid(ctx_, fmt::format("{}: texture {} names image {}, which does not exist", owner,
                                textureIndex, source.source));
    }
    TextureRef ref;
    ref.image = sceneImage(source.source);
    ref.texCoord = texCoord;
    if (texCoord != 0 && texCoord != 1) {
      ctx_.warnings.push_back(
          fmt::format("{}: TEXCOORD_{} is not supported; TEXCOORD_0 used", owner, texCoord));
      ref.texCoord = 0;
    }
    ref.sampler = sampler(source.sampler, owner);
    return ref;
  }

  Sampler sampler(int index, const std::string& owner) const {
    Sampler result;
    if (index < 0) return result;
    if (static_cast<std::size_t>(index) >= model_.samplers.size()) {
      invalid(ctx_, fmt::format("{}: sampler {} does not exist", owner, index));
    }
    const tinygltf::Sampler& source = model_.samplers[static_cast<std::size_t>(index)];
    // -1 is tinygltf's "not given": keep our defaults silently; other unknown values warn.
    if (knownFilter(source.magFilter, false)) result.magFilter = source.magFilter;
    if (knownFilter(source.minFilter, true)) result.minFilter = source.minFilter;
    if (knownWrap(source.wrapS)) result.wrapS = source.wrapS;
    if (knownWrap(source.wrapT)) result.wrapT = source.wrapT;
    const bool filtersOk = (source.magFilter == -1 || knownFilter(source.magFilter, false)) &&
                           (source.minFilter == -1 || knownFilter(source.minFilter, true));
    if (!filtersOk || !knownWrap(source.wrapS) || !knownWrap(source.wrapT)) {
      ctx_.warnOnce(
          fmt::format("sampler {} has invalid filter or wrap values; defaults used", index));
    }
    return result;
  }

  // The Scene::images index of glTF image `index`, moving the decoded image over on first use.
  int sceneImage(int index) {
    if (const auto it = imageRemap_.find(index); it != imageRemap_.end()) return it->second;
    if (const auto failed = ctx_.imageErrors.find(index); failed != ctx_.imageErrors.end()) {
      throw failed->second;
    }
    const auto decoded = ctx_.images.find(index);
    if (decoded == ctx_.images.end()) throw missingImageError(index);
    scene_.images.push_back(std::move(decoded->second));
    ctx_.images.erase(decoded);
    const int sceneIndex = static_cast<int>(scene_.images.size()) - 1;
    imageRemap_.emplace(index, sceneIndex);
    return sceneIndex;
  }

  // tinygltf keeps an external image it could not read as a bare URI; say why it is missing.
  Error missingImageError(int index) const {
    const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
    const std::string decodedUri = tinygltf::dlib::urldecode(image.uri);
    if (const auto it = ctx_.fileErrors.find(uriKey(decodedUri)); it != ctx_.fileErrors.end()) {
      return it->second;
    }
    return Error(ErrorCode::Invalid,
                 fmt::format("{} could not be loaded", imageLabel(image, index)), ctx_.displayName);
  }

  const tinygltf::Model& model_;
  LoadContext& ctx_;
  Scene& scene_;
  std::map<int, int> imageRemap_;
};

// ---------------------------------------------------------------------------------------------
// Nodes, lights, cameras.

glm::mat4 nodeMatrix(const tinygltf::Node& node) {
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
    for (int node : rootNodes()) visit(node, glm::mat4(1.0F), 0, "the scene");
    if (scene_.triangleCount() == 0) invalid(ctx_, "the asset has no triangle geometry");
    for (std::size_t i = 0; i < model_.materials.size(); ++i) {
      scene_.materials.push_back(materials_.convert(static_cast<int>(i)));
    }
    materials_.warnAboutUnusedFailures();
    scene_.computeBounds();
    checkBounds();
    scene_.warnings = std::move(ctx_.warnings);
    return std::move(scene_);
  }

 private:
  bool usesExtension(const std::string& name) const {
    const auto& used = model_.extensionsUsed;
    return std::find(used.begin(), used.end(), name) != used.end();
  }

  // The default scene's roots (scene 0 when none is named); with no scenes at all, every node
  // that is nobody's child.
  std::vector<int> rootNodes() const {
    if (!model_.scenes.empty()) {
      const int chosen = model_.defaultScene >= 0 && static_cast<std::size_t>(model_.defaultScene) <
                                                         model_.scenes.size()
                             ? model_.defaultScene
                             : 0;
      if (model_.defaultScene >= 0 && chosen != model_.defaultScene) {
        ctx_.warnings.push_back(
            fmt::format("default scene {} does not exist; scene 0 used", model_.defaultScene));
      }
      return model_.scenes[static_cast<std::size_t>(chosen)].nodes;
    }
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes) {
      for (int child : node.children) {
        if (child >= 0 && static_cast<std::size_t>(child) < isChild.size()) {
          isChild[static_cast<std::size_t>(child)] = true;
        }
      }
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < isChild.size(); ++i) {
      if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
    return roots;
  }

  void visit(int index, const glm::mat4& parent, int depth, const std::string& referrer) {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size()) {
      invalid(ctx_, fmt::format("{} refers to node {}, which does not exist", referrer, index));
    }
    const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(index)];
    const std::string where = label("node", index, node.name);
    if (onPath_[static_cast<std::size_t>(index)]) {
      invalid(ctx_, fmt::format("the node hierarchy has a cycle: {} is its own ancestor", where));
    }
    if (depth >= kMaxNodeDepth) {
      invalid(ctx_, fmt::format("the node hierarchy is deeper than {} levels (at {})",
                                kMaxNodeDepth, where));
    }
    if (++visits_ > kMaxNodeVisits) {
      tooLarge(ctx_, fmt::format("the node hierarchy expands to more than {} node instances",
                                 kMaxNodeVisits));
    }
    const glm::mat4 world = parent * nodeMatrix(node);
    if (!isFinite(world)) invalid(ctx_, fmt::format("{} has a non-finite transform", where));
    if (node.skin >= 0) ctx_.warnOnce("skins are not supported; meshes are rendered in bind pose");
    if (node.mesh >= 0) addInstance(node.mesh, world, where);
    if (node.camera >= 0) addCamera(node.camera, world, where);
    addLight(node, world, where);
    onPath_[static_cast<std::size_t>(index)] = true;
    for (int child : node.children) visit(child, world, depth + 1, where);
    onPath_[static_cast<std::size_t>(index)] = false;
  }

  void addInstance(int meshIndex, const glm::mat4& world, const std::string& where) {
    if (static_cast<std::size_t>(meshIndex) >= model_.meshes.size()) {
      invalid(ctx_, fmt::format("{} refers to mesh {}, which does not exist", where, meshIndex));
    }
    const int sceneMesh = convertedMesh(meshIndex);
    if (sceneMesh < 0) return;
    trianglesDrawn_ += meshTriangles_[static_cast<std::size_t>(sceneMesh)];
    if (trianglesDrawn_ > ctx_.limits.maxTriangles) {
      tooLarge(ctx_, fmt::format("the asset draws more than {} triangles (at {})",
                                 ctx_.limits.maxTriangles, where));
    }
    scene_.instances.push_back({sceneMesh, world});
  }

  // The Scene::meshes index of glTF mesh `index`, converting it on first use; -1 when it has no
  // triangles.
  int convertedMesh(int index) {
    int& slot = meshRemap_[static_cast<std::size_t>(index)];
    if (slot != -1) return slot;
    const tinygltf::Mesh& source = model_.meshes[static_cast<std::size_t>(index)];
    Mesh mesh;
    mesh.name = source.name;
    std::size_t triangles = 0;
    for (std::size_t p = 0; p < source.primitives.size(); ++p) {
      auto primitive = primitives_.convert(index, static_cast<int>(p), trianglesDrawn_ + triangles);
      if (!primitive) continue;
      triangles += primitive->indices.size() / 3;
      mesh.primitives.push_back(std::move(*primitive));
    }
    if (mesh.primitives.empty()) {
      slot = -2;  // converted, nothing to draw
      return -1;
    }
    slot = static_cast<int>(scene_.meshes.size());
    scene_.meshes.push_back(std::move(mesh));
    meshTriangles_.push_back(triangles);
    return slot;
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
                                        label("camera", index, source.name), where));
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
                      label("light", index, source.name), where));
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
  std::size_t visits_ = 0;
  std::size_t trianglesDrawn_ = 0;
};

// ---------------------------------------------------------------------------------------------
// Loading.

constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kGlbJsonChunk = 0x4E4F534A;

std::uint32_t readLittleEndian32(const std::uint8_t* bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8U) |
         (static_cast<std::uint32_t>(bytes[2]) << 16U) |
         (static_cast<std::uint32_t>(bytes[3]) << 24U);
}

bool isGlb(const std::vector<std::uint8_t>& bytes) {
  return bytes.size() >= 4 && readLittleEndian32(bytes.data()) == kGlbMagic;
}

// The JSON chunk of a GLB; nullopt when the header is broken (tinygltf then says how).
std::optional<std::string_view> glbJson(const std::vector<std::uint8_t>& bytes) {
  if (bytes.size() < 20 || readLittleEndian32(bytes.data() + 16) != kGlbJsonChunk) {
    return std::nullopt;
  }
  const std::uint32_t length = readLittleEndian32(bytes.data() + 12);
  if (length > bytes.size() - 20) return std::nullopt;
  return std::string_view(reinterpret_cast<const char*>(bytes.data() + 20), length);
}

std::size_t jsonSize(const json& value, const char* key, std::size_t fallback = 0) {
  const auto it = value.find(key);
  return it != value.end() && it->is_number_unsigned() ? it->get<std::size_t>() : fallback;
}

// tinygltf reads an image's bufferView bytes without checking that they lie inside the buffer;
// check that here, on the JSON, before it gets the chance.
void checkImageBufferViews(const json& document, const LoadContext& ctx) {
  const json empty = json::array();
  const json& images = document.contains("images") ? document["images"] : empty;
  const json& views = document.contains("bufferViews") ? document["bufferViews"] : empty;
  const json& buffers = document.contains("buffers") ? document["buffers"] : empty;
  for (std::size_t i = 0; i < images.size(); ++i) {
    const std::size_t view = jsonSize(images[i], "bufferView", SIZE_MAX);
    if (view == SIZE_MAX) continue;
    if (view >= views.size()) {
      invalid(ctx, fmt::format("invalid glTF: /images/{}/bufferView names bufferView {}, which "
                               "does not exist",
                               i, view));
    }
    const std::size_t buffer = jsonSize(views[view], "buffer", SIZE_MAX);
    const std::size_t offset = jsonSize(views[view], "byteOffset");
    const std::size_t length = jsonSize(views[view], "byteLength");
    const std::size_t bufferLength =
        buffer < buffers.size() ? jsonSize(buffers[buffer], "byteLength") : 0;
    if (offset > bufferLength || length > bufferLength - offset) {
      invalid(ctx, fmt::format("invalid glTF: bufferView {} of image {} lies outside its buffer",
                               view, i));
    }
  }
}

// Required extensions we lack fail the load; optional ones are ignored with a warning.
void checkExtensions(const json& document, LoadContext& ctx) {
  std::vector<std::string> unsupported;
  for (const json& name : document.value("extensionsRequired", json::array())) {
    if (kSupportedExtensions.count(name.get<std::string>()) == 0) {
      unsupported.push_back(name.get<std::string>());
    }
  }
  if (!unsupported.empty()) {
    invalid(ctx, fmt::format("the asset requires unsupported glTF extension(s): {}",
                             fmt::join(unsupported, ", ")));
  }
  for (const json& name : document.value("extensionsUsed", json::array())) {
    if (kSupportedExtensions.count(name.get<std::string>()) == 0) {
      ctx.warnOnce(fmt::format("optional glTF extension {} is not supported; ignored",
                               name.get<std::string>()));
    }
  }
}

void precheckJson(std::string_view text, LoadContext& ctx) {
  json document;
  try {
    document = json::parse(text.begin(), text.end());
  } catch (const json::exception& error) {
    invalid(ctx, fmt::format("the glTF JSON does not parse: {}", error.what()));
  }
  schema::Checker(ctx.displayName).checkObject(document, schema::root(), "");
  const std::string version = document["asset"]["version"].get<std::string>();
  if (version.rfind("2.", 0) != 0) {
    invalid(ctx, fmt::format("glTF version {} is not supported (2.x only)", version));
  }
  checkExtensions(document, ctx);
  checkImageBufferViews(document, ctx);
}

[[noreturn]] void throwParseFailure(const LoadContext& ctx, const std::string& tinygltfError) {
  if (!ctx.fileErrors.empty()) throw ctx.fileErrors.begin()->second;
  std::string message = tinygltfError;
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  if (message.empty()) message = "no detail given";
  invalid(ctx, fmt::format("the glTF could not be parsed: {}", message));
}

void addParserWarnings(LoadContext& ctx, const std::string& text) {
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) ctx.warnOnce("glTF parser: " + text.substr(start, end - start));
    start = end + 1;
  }
}

tinygltf::Model parseModel(const std::vector<std::uint8_t>& bytes, LoadContext& ctx) {
  const bool binary = isGlb(bytes);
  if (!binary) {
    precheckJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), ctx);
  } else if (const auto text = glbJson(bytes)) {
    precheckJson(*text, ctx);
  }
  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks({&fileExistsCallback, &expandFilePathCallback, &readWholeFileCallback,
                         &writeWholeFileCallback, &ctx});
  parser.SetImageLoader(&loadImageCallback, &ctx);
  tinygltf::Model model;
  std::string error;
  std::string warning;
  const auto size = static_cast<unsigned int>(bytes.size());
  const bool parsed =
      binary ? parser.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(), size, "")
             : parser.LoadASCIIFromString(&model, &error, &warning,
                                          reinterpret_cast<const char*>(bytes.data()), size, "");
  if (ctx.fatal) throw *ctx.fatal;
  if (!parsed) throwParseFailure(ctx, error);
  addParserWarnings(ctx, warning);
  addParserWarnings(ctx, error);  // tinygltf also reports non-fatal problems as errors
  return model;
}

Scene loadModel(const std::vector<std::uint8_t>& bytes, LoadContext& ctx) {
  if (bytes.size() > ctx.limits.maxFileBytes || bytes.size() > UINT_MAX) {
    tooLarge(ctx, fmt::format("the asset is {} bytes, over the limit of {}", bytes.size(),
                              std::min<std::size_t>(ctx.limits.maxFileBytes, UINT_MAX)));
  }
  if (bytes.empty()) invalid(ctx, "the asset is empty");
  const tinygltf::Model model = parseModel(bytes, ctx);
  return SceneBuilder(model, ctx).build();
}

// Every failure leaves as lgh::Error: the loader's own, and whatever the standard library or
// tinygltf throws on hostile input.
template <typename Load>
Scene guarded(const std::string& displayName, Load&& load) {
  try {
    return load();
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw Error(ErrorCode::TooLarge, "the asset needs more memory than is available", displayName);
  } catch (const std::exception& error) {
    throw Error(ErrorCode::Invalid, fmt::format("the asset could not be loaded: {}", error.what()),
                displayName);
  }
}

std::vector<std::uint8_t> readAssetFile(const fs::path& path, const LoadContext& ctx) {
  const std::uintmax_t size = fs::file_size(path);
  if (size > ctx.limits.maxFileBytes) {
    tooLarge(ctx, fmt::format("the asset is {} bytes, over the limit of {}", size,
                              ctx.limits.maxFileBytes));
  }
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  std::ifstream stream(path, std::ios::binary);
  if (!stream.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) {
    throw Error(ErrorCode::NotFound, "the asset could not be read", ctx.displayName);
  }
  return bytes;
}

}  // namespace

Scene loadGltfFile(const fs::path& assetRoot, const std::string& relativePath,
                   const SceneLoadLimits& limits) {
  return guarded(relativePath, [&] {
    LoadContext ctx;
    ctx.displayName = relativePath;
    ctx.limits = limits;
    ctx.sideFiles = SideFiles::Directory;
    ctx.root = assetRoot;
    const fs::path path = resolveAssetPath(assetRoot, relativePath, relativePath);
    ctx.baseDir = checkRelativeAssetPath(relativePath, relativePath).parent_path();
    return loadModel(readAssetFile(path, ctx), ctx);
  });
}

Scene loadGlbBytes(const std::vector<std::uint8_t>& bytes, const std::string& displayName,
                   const SceneLoadLimits& limits) {
  return guarded(displayName, [&] {
    LoadContext ctx;
    ctx.displayName = displayName;
    ctx.limits = limits;
    ctx.sideFiles = SideFiles::None;
    return loadModel(bytes, ctx);
  });
}

Scene loadGltfFromMemory(const std::string& gltfName,
                         const std::map<std::string, std::vector<std::uint8_t>>& files,
                         const SceneLoadLimits& limits) {
  return guarded(gltfName, [&] {
    LoadContext ctx;
    ctx.displayName = gltfName;
    ctx.limits = limits;
    ctx.sideFiles = SideFiles::Memory;
    for (const auto& [name, bytes] : files) {
      // Uploaded names that could not be referenced legally are simply never found.
      ctx.memoryFiles.emplace(uriKey(name), &bytes);
    }
    const fs::path name = checkRelativeAssetPath(gltfName, gltfName);
    ctx.baseDir = name.parent_path();
    const auto it = ctx.memoryFiles.find(name.generic_string());
    if (it == ctx.memoryFiles.end()) {
      throw Error(ErrorCode::NotFound,
                  fmt::format("'{}' is not among the uploaded files", gltfName), gltfName);
    }
    return loadModel(*it->second, ctx);
  });
}

}  // namespace lgh
