#include "scene/scene_cache.hpp"

#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/stopwatch.hpp"
#include "gl/gl_api.hpp"
#include "scene/asset_path.hpp"
#include "scene/atrium_scene.hpp"
#include "scene/demo_scene.hpp"
#include "scene/gltf/gltf_loader.hpp"

namespace lgh {
namespace {

std::uint64_t fnv1a(const std::vector<std::uint8_t>& bytes) {
  std::uint64_t hash = 1469598103934665603ULL;
  for (std::uint8_t byte : bytes) {
    hash ^= byte;
    hash *= 1099511628211ULL;
  }
  return hash;
}

}  // namespace

SceneCache::SceneCache(const RendererOptions& options) : options_(options) {
  GLfloat anisotropy = 1.0F;
  glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &anisotropy);
  maxAnisotropy_ = anisotropy;
}

namespace {

// The options' part of a cache key ("" for the defaults, so default keys stay as they were).
std::string optionsKey(const SceneLoadOptions& options) {
  std::string key;
  if (options.animation) {
    key += fmt::format("|animation={}@{}", options.animation->index, options.animation->time);
  }
  if (!options.materialVariant.empty()) key += "|variant=" + options.materialVariant;
  if (options.ignoreUnsupportedExtensions) key += "|ignore-unsupported";
  return key;
}

// Texture compression changes the upload, whatever the source (the builtin scenes included).
std::string uploadKey(const SceneLoadOptions& options) {
  return options.textureCompression == TextureCompression::Bc ? "|bc" : "";
}

}  // namespace

std::string SceneCache::keyFor(const SceneSource& source, const SceneLoadOptions& options) const {
  const std::string base = sourceKey(source);
  if (base.empty()) return base;
  if (source.kind == SceneSource::Kind::Builtin) return base + uploadKey(options);
  return base + optionsKey(options) + uploadKey(options);
}

std::string SceneCache::sourceKey(const SceneSource& source) const {
  switch (source.kind) {
    case SceneSource::Kind::Builtin:
      return source.builtin == BuiltinScene::Demo
                 ? "demo"
                 : "builtin:" + std::string(enumName(source.builtin));
    case SceneSource::Kind::InlineGlb:
      return fmt::format("glb:{:016x}:{}", fnv1a(source.glbBytes), source.glbBytes.size());
    case SceneSource::Kind::UploadedGltf: {
      std::string key = "upload:" + source.gltfFileName;
      for (const auto& [name, bytes] : source.uploadedFiles) {
        key += fmt::format(":{}={:016x}", name, fnv1a(bytes));
      }
      return key;
    }
    case SceneSource::Kind::AssetPath: {
      auto path = resolveAssetPath(options_.assetRoot, source.assetPath, "/scene/asset");
      std::error_code error;
      auto size = std::filesystem::file_size(path, error);
      auto mtime = std::filesystem::last_write_time(path, error).time_since_epoch().count();
      // A .gltf's side files may change without the .gltf changing: key by the folder's newest
      // mtime too, cheaply, by the .gltf's own folder.
      auto folderTime =
          std::filesystem::last_write_time(path.parent_path(), error).time_since_epoch().count();
      return fmt::format("file:{}:{}:{}:{}", path.string(), size, mtime, folderTime);
    }
  }
  return {};
}

Scene SceneCache::load(const SceneSource& source, const SceneLoadOptions& options) const {
  SceneLoadLimits limits;
  limits.maxTriangles = options_.maxTriangles;
  limits.maxTextureSize = options_.maxTextureSize;
  switch (source.kind) {
    case SceneSource::Kind::Builtin:
      return source.builtin == BuiltinScene::Atrium ? makeAtriumScene() : makeDemoScene();
    case SceneSource::Kind::InlineGlb:
      return loadGlbBytes(source.glbBytes,
                          source.displayName.empty() ? "inline.glb" : source.displayName, limits,
                          options);
    case SceneSource::Kind::UploadedGltf:
      return loadGltfFromMemory(source.gltfFileName, source.uploadedFiles, limits, options);
    case SceneSource::Kind::AssetPath:
      return loadGltfFile(options_.assetRoot, source.assetPath, limits, options);
  }
  return makeDemoScene();
}

SceneCache::Lookup SceneCache::get(const SceneSource& source, const SceneLoadOptions& options) {
  Lookup lookup;
  const std::string key = keyFor(source, options);
  for (auto it = slots_.begin(); it != slots_.end(); ++it) {
    if (it->key != key) continue;
    slots_.splice(slots_.begin(), slots_, it);
    ++hits_;
    lookup.entry = slots_.front().entry;
    lookup.hit = true;
    evictOverBudget();  // acceleration structures built since may have grown the entries
    return lookup;
  }
  ++misses_;
  const Stopwatch loadTimer;
  auto entry = std::make_shared<CachedScene>();
  entry->scene = load(source, options);
  lookup.loadMs = loadTimer.elapsedMs();
  const Stopwatch uploadTimer;
  entry->gpu = std::make_unique<GpuScene>(
      entry->scene, GpuSceneOptions{maxAnisotropy_, options.textureCompression});
  lookup.uploadMs = uploadTimer.elapsedMs();
  lookup.entry = entry;
  slots_.push_front({key, entry});
  evictOverBudget();
  return lookup;
}

void SceneCache::evictOverBudget() {
  std::size_t total = 0;
  for (const Slot& slot : slots_) total += slot.entry->gpuBytes();
  while (slots_.size() > 1 && total > options_.sceneCacheBytes) {
    const std::size_t bytes = slots_.back().entry->gpuBytes();
    spdlog::info("scene cache: evicting {} ({} bytes)", slots_.back().key, bytes);
    total -= bytes;
    slots_.pop_back();
  }
}

SceneCacheStats SceneCache::stats() const {
  SceneCacheStats stats;
  stats.hits = hits_;
  stats.misses = misses_;
  stats.entries = slots_.size();
  for (const Slot& slot : slots_) stats.bytes += slot.entry->gpuBytes();
  return stats;
}

}  // namespace lgh
