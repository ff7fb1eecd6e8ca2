// The loader's entry points: read the asset, pre-check its container and JSON (nesting, schema
// types, glTF version, the document's references and ranges, extensions) before tinygltf sees it,
// parse it through tinygltf with the sandboxed file and image callbacks, and build the Scene; every
// failure leaves as lgh::Error.
//
// The stages, one file each in this folder:
//   glb_container       the GLB header and chunks, strictly
//   schema_check        JSON member types, before tinygltf (which drops wrongly typed members)
//   document_check      what the specification requires beyond types (as the Khronos validator)
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

#include "core/json_shape.hpp"
#include "lgh/error.hpp"
#include "scene/asset_path.hpp"
#include "scene/gltf/document_check.hpp"
#include "scene/gltf/geometry_decompression.hpp"
#include "scene/gltf/glb_container.hpp"
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

// glTF's own structure nests 7 levels deep (/meshes/0/primitives/0/targets/0/POSITION); extras
// and extensions may nest further, but not without bound. The value count bounds what the JSON
// costs in memory, here and again inside tinygltf.
constexpr JsonShapeLimits kGltfJsonLimits{64, 4'000'000};

// The JSON checks; returns replacement JSON text when the document had to be patched for tinygltf.
// `glbBinBytes`: for a GLB, the size of its BIN chunk (0: none).
std::optional<std::string> precheckJson(std::string_view text,
                                        std::optional<std::size_t> glbBinBytes, LoadContext& ctx) {
  if (const auto excess = findJsonShapeExcess(text, kGltfJsonLimits)) {
    tooLarge(ctx, "the glTF JSON " + excess->describe(kGltfJsonLimits));
  }
  json document;
  try {
    document = json::parse(text.begin(), text.end());
  } catch (const json::exception& error) {
    invalid(ctx, fmt::format("the glTF JSON does not parse: {}", error.what()));
  }
  checkSchema(document, ctx.displayName);
  const std::string version = document["asset"]["version"].get<std::string>();
  if (version.rfind("2.", 0) != 0) {
    invalid(ctx,
            fmt::format("/asset/version: glTF version {} is not supported (2.x only)", version));
  }
  checkDocument(document, {ctx.displayName, glbBinBytes});
  checkExtensions(document, ctx);
  // The stubs come after the checks: what the validator sees is the asset as sent.
  const bool meshopt = stubMeshoptFallbackBuffers(document, glbBinBytes.has_value());
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
  const bool binary = hasGlbMagic(original);
  std::vector<std::uint8_t> patched;
  if (binary) {
    const GlbChunks chunks = readGlbContainer(original, ctx);
    const auto text = precheckJson(chunks.json, chunks.binBytes, ctx);
    for (std::uint32_t type : chunks.unknownChunkTypes) {
      ctx.warnOnce(fmt::format("GLB chunk of unknown type 0x{:08x} ignored", type));
    }
    if (text || !chunks.unknownChunkTypes.empty()) {
      patched = rebuiltGlb(original, chunks, text ? std::string_view(*text) : chunks.json);
    }
  } else {
    const auto text = precheckJson(
        std::string_view(reinterpret_cast<const char*>(original.data()), original.size()),
        std::nullopt, ctx);
    if (text) patched.assign(text->begin(), text->end());
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

Scene loadSceneSource(const SceneSource& source, const std::filesystem::path& assetRoot,
                      const SceneLoadLimits& limits, const SceneLoadOptions& options) {
  switch (source.kind) {
    case SceneSource::Kind::InlineGlb:
      return loadGlbBytes(source.glbBytes,
                          source.displayName.empty() ? "inline.glb" : source.displayName, limits,
                          options);
    case SceneSource::Kind::UploadedGltf:
      return loadGltfFromMemory(source.gltfFileName, source.uploadedFiles, limits, options);
    case SceneSource::Kind::AssetPath:
      return loadGltfFile(assetRoot, source.assetPath, limits, options);
    case SceneSource::Kind::Builtin:
      break;
  }
  throw Error(ErrorCode::Internal, "built-in scenes are made, not loaded");
}

}  // namespace lgh
