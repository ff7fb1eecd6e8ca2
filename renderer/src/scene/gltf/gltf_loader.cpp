// The loader's entry points: read the asset, pre-check its JSON (schema types, glTF version,
// extensions, image bufferViews) before tinygltf sees it, parse it through tinygltf with the
// sandboxed file and image callbacks, and build the Scene; every failure leaves as lgh::Error.
//
// The stages, one file each in this folder:
//   schema_check        JSON member types, before tinygltf (which drops wrongly typed members)
//   side_files          buffer and image URIs, through the asset sandbox (tinygltf's file access)
//   image_decoding      texture images: size limit from the header, then our image I/O
//   accessor_reader     bounds-checked accessor reads
//   geometry_decompression  KHR_draco_mesh_compression, EXT_meshopt_compression -> plain buffers
//   primitive_converter glTF primitives -> triangle, line and point lists with normals, tangents
//   deformation         morph targets and skins applied to a primitive
//   animation_pose      an animation sampled at one time
//   material_converter  materials, textures, samplers (material_extensions: KHR_materials_*,
//                       texture_transform: KHR_texture_transform)
//   scene_builder       the node hierarchy -> instances, cameras, lights
// load_context holds what a load carries through them; tinygltf.hpp configures tinygltf.
#include "scene/gltf/gltf_loader.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <fstream>
#include <functional>
#include <new>
#include <optional>
#include <set>
#include <string_view>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "lgh/error.hpp"
#include "scene/asset_path.hpp"
#include "scene/gltf/geometry_decompression.hpp"
#include "scene/gltf/image_decoding.hpp"
#include "scene/gltf/load_context.hpp"
#include "scene/gltf/scene_builder.hpp"
#include "scene/gltf/schema_check.hpp"
#include "scene/gltf/side_files.hpp"
#include "scene/gltf/tinygltf.hpp"

namespace lgh {
namespace gltf {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Extensions this loader implements; a REQUIRED extension outside this set fails the load, unless
// the request says to ignore it. KHR_texture_basisu is not here: no maintained transcoder is a
// Debian package, so a texture that only has a KTX2 image is refused (or, optional, falls back to
// the texture's plain source).
const std::set<std::string, std::less<>> kSupportedExtensions = {
    "KHR_lights_punctual",        "KHR_materials_emissive_strength",
    "KHR_mesh_quantization",      "KHR_texture_transform",
    "KHR_materials_unlit",        "KHR_materials_clearcoat",
    "KHR_materials_sheen",        "KHR_materials_specular",
    "KHR_materials_ior",          "KHR_materials_transmission",
    "KHR_materials_volume",       "KHR_materials_variants",
    "KHR_draco_mesh_compression", "EXT_meshopt_compression",
    "EXT_texture_webp",           "MSFT_texture_dds"};

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
  if (!unsupported.empty() && !ctx.options.ignoreUnsupportedExtensions) {
    invalid(ctx, fmt::format("the asset requires unsupported glTF extension(s): {} (set "
                             "settings.ignore_unsupported_extensions to render it anyway)",
                             fmt::join(unsupported, ", ")));
  }
  for (const std::string& name : unsupported) {
    ctx.warnOnce(
        fmt::format("required glTF extension {} is not supported; rendered without it "
                    "(settings.ignore_unsupported_extensions)",
                    name));
  }
  for (const json& name : document.value("extensionsUsed", json::array())) {
    const auto& text = name.get_ref<const std::string&>();
    if (kSupportedExtensions.count(text) == 0 &&
        std::find(unsupported.begin(), unsupported.end(), text) == unsupported.end()) {
      ctx.warnOnce(fmt::format("optional glTF extension {} is not supported; ignored",
                               name.get<std::string>()));
    }
  }
}

// EXT_meshopt_compression's fallback buffers carry no data (no uri, or past the GLB's BIN chunk),
// which tinygltf refuses. They are only read through decoded bufferViews, so give each one a single
// byte of data for tinygltf's sake; true when the document changed.
bool stubMeshoptFallbackBuffers(json& document, bool binary) {
  if (!document.contains("buffers") || !document["buffers"].is_array()) return false;
  bool changed = false;
  json& buffers = document["buffers"];
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    json& buffer = buffers[i];
    const json* extension = nullptr;
    for (const char* name : {"EXT_meshopt_compression", "KHR_meshopt_compression"}) {
      if (buffer.contains("extensions") && buffer["extensions"].is_object() &&
          buffer["extensions"].contains(name)) {
        extension = &buffer["extensions"][name];
      }
    }
    if (extension == nullptr || !extension->is_object() || !extension->value("fallback", false) ||
        buffer.contains("uri")) {
      continue;
    }
    if (binary && i == 0) continue;  // the BIN chunk itself
    buffer["uri"] = "data:application/octet-stream;base64,AA==";
    buffer["byteLength"] = 1;
    changed = true;
  }
  return changed;
}

// KHR_draco_mesh_compression's index accessors have no bufferView (the indices are in the Draco
// stream), which tinygltf refuses. Point each at a one-byte stub view for tinygltf's sake; the
// Draco stage (geometry_decompression) points it at the decoded indices. True when changed.
bool stubDracoIndexViews(json& document) {
  if (!document.contains("meshes") || !document.contains("accessors") ||
      !document.contains("buffers") || document["buffers"].empty()) {
    return false;
  }
  json& accessors = document["accessors"];
  std::optional<std::size_t> stub;
  for (json& mesh : document["meshes"]) {
    if (!mesh.contains("primitives")) continue;
    for (json& primitive : mesh["primitives"]) {
      const bool draco = primitive.contains("extensions") &&
                         primitive["extensions"].contains("KHR_draco_mesh_compression");
      if (!draco || !primitive.contains("indices") || !primitive["indices"].is_number_unsigned()) {
        continue;
      }
      const auto index = primitive["indices"].get<std::size_t>();
      if (index >= accessors.size() || accessors[index].contains("bufferView")) continue;
      if (!stub) {
        document["bufferViews"].push_back({{"buffer", 0}, {"byteLength", 1}});
        stub = document["bufferViews"].size() - 1;
      }
      accessors[index]["bufferView"] = *stub;
    }
  }
  return stub.has_value();
}

// A GLB with its JSON chunk replaced by `text` (padded with spaces), other chunks unchanged.
std::vector<std::uint8_t> replaceGlbJson(const std::vector<std::uint8_t>& bytes,
                                         const std::string& text) {
  const std::uint32_t oldLength = readLittleEndian32(bytes.data() + 12);
  std::string padded = text;
  while (padded.size() % 4 != 0) padded.push_back(' ');
  std::vector<std::uint8_t> out(bytes.begin(), bytes.begin() + 12);
  auto put32 = [&out](std::uint32_t value) {
    for (int b = 0; b < 4; ++b) out.push_back(static_cast<std::uint8_t>(value >> (8 * b)));
  };
  put32(static_cast<std::uint32_t>(padded.size()));
  put32(kGlbJsonChunk);
  out.insert(out.end(), padded.begin(), padded.end());
  out.insert(out.end(), bytes.begin() + 20 + oldLength, bytes.end());
  const auto total = static_cast<std::uint32_t>(out.size());
  for (int b = 0; b < 4; ++b) {
    out[8 + static_cast<std::size_t>(b)] = static_cast<std::uint8_t>(total >> (8 * b));
  }
  return out;
}

// The JSON checks; returns replacement JSON text when the document had to be patched for tinygltf.
std::optional<std::string> precheckJson(std::string_view text, LoadContext& ctx, bool binary) {
  json document;
  try {
    document = json::parse(text.begin(), text.end());
  } catch (const json::exception& error) {
    invalid(ctx, fmt::format("the glTF JSON does not parse: {}", error.what()));
  }
  checkSchema(document, ctx.displayName);
  const std::string version = document["asset"]["version"].get<std::string>();
  if (version.rfind("2.", 0) != 0) {
    invalid(ctx, fmt::format("glTF version {} is not supported (2.x only)", version));
  }
  checkExtensions(document, ctx);
  checkImageBufferViews(document, ctx);
  const bool meshopt = stubMeshoptFallbackBuffers(document, binary);
  const bool draco = stubDracoIndexViews(document);
  if (meshopt || draco) return document.dump();
  return std::nullopt;
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

tinygltf::Model parseModel(const std::vector<std::uint8_t>& original, LoadContext& ctx) {
  const bool binary = isGlb(original);
  std::vector<std::uint8_t> patched;
  if (!binary) {
    const auto text = precheckJson(
        std::string_view(reinterpret_cast<const char*>(original.data()), original.size()), ctx,
        false);
    if (text) patched.assign(text->begin(), text->end());
  } else if (const auto json = glbJson(original)) {
    if (const auto text = precheckJson(*json, ctx, true)) patched = replaceGlbJson(original, *text);
  }
  const std::vector<std::uint8_t>& bytes = patched.empty() ? original : patched;
  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks(sandboxedFileCallbacks(ctx));
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
  tinygltf::Model model = parseModel(bytes, ctx);
  decompressGeometry(model, ctx);
  return buildScene(model, ctx);
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
}  // namespace gltf

Scene loadGltfFile(const std::filesystem::path& assetRoot, const std::string& relativePath,
                   const SceneLoadLimits& limits, const SceneLoadOptions& options) {
  return gltf::guarded(relativePath, [&] {
    gltf::LoadContext ctx;
    ctx.displayName = relativePath;
    ctx.limits = limits;
    ctx.options = options;
    ctx.sideFiles = gltf::SideFiles::Directory;
    ctx.root = assetRoot;
    const std::filesystem::path path = resolveAssetPath(assetRoot, relativePath, relativePath);
    ctx.baseDir = checkRelativeAssetPath(relativePath, relativePath).parent_path();
    return gltf::loadModel(gltf::readAssetFile(path, ctx), ctx);
  });
}

Scene loadGlbBytes(const std::vector<std::uint8_t>& bytes, const std::string& displayName,
                   const SceneLoadLimits& limits, const SceneLoadOptions& options) {
  return gltf::guarded(displayName, [&] {
    gltf::LoadContext ctx;
    ctx.displayName = displayName;
    ctx.limits = limits;
    ctx.options = options;
    ctx.sideFiles = gltf::SideFiles::None;
    return gltf::loadModel(bytes, ctx);
  });
}

Scene loadGltfFromMemory(const std::string& gltfName,
                         const std::map<std::string, std::vector<std::uint8_t>>& files,
                         const SceneLoadLimits& limits, const SceneLoadOptions& options) {
  return gltf::guarded(gltfName, [&] {
    gltf::LoadContext ctx;
    ctx.displayName = gltfName;
    ctx.limits = limits;
    ctx.options = options;
    ctx.sideFiles = gltf::SideFiles::Memory;
    for (const auto& [name, bytes] : files) {
      // Uploaded names that could not be referenced legally are simply never found.
      ctx.memoryFiles.emplace(gltf::uriKey(name), &bytes);
    }
    const std::filesystem::path name = checkRelativeAssetPath(gltfName, gltfName);
    ctx.baseDir = name.parent_path();
    const auto it = ctx.memoryFiles.find(name.generic_string());
    if (it == ctx.memoryFiles.end()) {
      throw Error(ErrorCode::NotFound,
                  fmt::format("'{}' is not among the uploaded files", gltfName), gltfName);
    }
    return gltf::loadModel(*it->second, ctx);
  });
}

}  // namespace lgh
