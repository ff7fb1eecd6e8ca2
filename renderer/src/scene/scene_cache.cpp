#include "scene/scene_cache.hpp"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/stopwatch.hpp"
#include "gl/gl_api.hpp"
#include "lgh/error.hpp"
#include "scene/asset_path.hpp"
#include "scene/atrium_scene.hpp"
#include "scene/demo_scene.hpp"
#include "scene/geometry_layout.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/worker/scene_worker_pool.hpp"

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

void GpuSceneDeleter::operator()(GpuScene* scene) const {
  if (worker == nullptr || worker->sharesCurrentContext()) {
    delete scene;  // NOLINT(cppcoreguidelines-owning-memory): the owner's deleter
    return;
  }
  worker->post([scene] { delete scene; });  // NOLINT(cppcoreguidelines-owning-memory)
}

namespace {

std::unique_ptr<gl::Worker> makeGlWorker(const RendererOptions& options, const GlContext* context) {
  if (!options.glWorker || context == nullptr) return nullptr;
  try {
    auto worker = std::make_unique<gl::Worker>(context->createShared(), &context->api());
    spdlog::info("scene cache: scenes are uploaded ahead and freed on a GL worker ({})",
                 worker->info().contextPath);
    return worker;
  } catch (const std::exception& error) {
    spdlog::warn(
        "scene cache: no GL worker ({}); scenes are uploaded and freed on the render thread",
        error.what());
    return nullptr;
  }
}

constexpr std::int64_t kDefaultStagingBytes = std::int64_t{128} << 20;
constexpr std::size_t kRecycledTextureBytes = std::size_t{64} << 20;
constexpr std::size_t kRecycledBufferBytes = std::size_t{32} << 20;

std::unique_ptr<gl::StagingMemory> makeStaging(const RendererOptions& options,
                                               const GlContext* context, bool glWorker) {
  std::int64_t bytes = options.uploadStagingBytes;
  if (bytes < 0) {
    if (context == nullptr || glWorker || context->info().softwareRenderer) {
      spdlog::info("scene cache: no upload staging ({}): the render thread copies scenes' bytes",
                   glWorker ? "the GL worker uploads" : "a software rasterizer's copies are CPU's");
      return nullptr;
    }
    bytes = kDefaultStagingBytes;
  }
  if (bytes == 0) return nullptr;
  try {
    auto staging = std::make_unique<gl::StagingMemory>(static_cast<std::size_t>(bytes));
    spdlog::info(
        "scene cache: prefetch threads copy the scenes they parse of {} KiB or more into {} MiB "
        "of staging memory; the render thread uploads them as GPU copies",
        options.uploadStagingMinBytes >> 10, staging->capacity() >> 20);
    return staging;
  } catch (const std::exception& error) {
    spdlog::warn("scene cache: no upload staging ({}): the render thread copies scenes' bytes",
                 error.what());
    return nullptr;
  }
}

// What a scene's upload takes on the GPU, before it is made: vertices, indices and its images
// as RGBA8 with mipmaps.
std::size_t estimatedUploadBytes(const Scene& scene) {
  const GeometryLayout layout = geometryLayout(scene);
  std::size_t bytes = layout.vertexBytes() + layout.indexBytes();
  for (const Image8& image : scene.images) {
    bytes += static_cast<std::size_t>(std::max(image.width, 0)) *
             static_cast<std::size_t>(std::max(image.height, 0)) * 4 * 4 / 3;
  }
  return bytes;
}

}  // namespace

SceneCache::SceneCache(const RendererOptions& options, const GlContext* context)
    : options_(options),
      glWorker_(makeGlWorker(options, context)),
      staging_(makeStaging(options, context, glWorker_ != nullptr)) {
  if (!options_.sceneWorker.executable.empty()) {
    parsers_ = std::make_unique<worker::SceneWorkerPool>(options_.sceneWorker);
  }
  GLfloat anisotropy = 1.0F;
  glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &anisotropy);
  maxAnisotropy_ = anisotropy;
  textureCapabilities_ = TextureCapabilities::query();
  if (!glWorker_) {
    recycledTextures_ = gl::RecycledTextures::create(kRecycledTextureBytes);
    recycledBuffers_ = gl::RecycledBuffers::create(kRecycledBufferBytes);
  }
}

SceneCache::~SceneCache() = default;

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
  std::string base = sourceKey(source);
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
    case SceneSource::Kind::AssetPath:
      return assetKey(source.assetPath);
  }
  return {};
}

std::string SceneCache::assetKey(const std::string& assetPath) const {
  const auto now = std::chrono::steady_clock::now();
  if (const auto known = assetKeys_.find(assetPath);
      known != assetKeys_.end() && now - known->second.checked < kAssetKeyLifetime) {
    return known->second.key;
  }
  auto path = resolveAssetPath(options_.assetRoot, assetPath, "/scene/asset");
  std::error_code error;
  auto size = std::filesystem::file_size(path, error);
  auto mtime = std::filesystem::last_write_time(path, error).time_since_epoch().count();
  // A .gltf's side files may change without the .gltf changing: key by the folder's newest
  // mtime too, cheaply, by the .gltf's own folder.
  auto folderTime =
      std::filesystem::last_write_time(path.parent_path(), error).time_since_epoch().count();
  std::string key = fmt::format("file:{}:{}:{}:{}", path.string(), size, mtime, folderTime);
  if (assetKeys_.size() >= kMaxAssetKeys) {
    std::erase_if(assetKeys_, [&](const auto& entry) {
      return now - entry.second.checked >= kAssetKeyLifetime;
    });
    if (assetKeys_.size() >= kMaxAssetKeys) assetKeys_.clear();
  }
  const bool sized = size != static_cast<std::uintmax_t>(-1);  // file_size's error value
  assetKeys_[assetPath] = {key, sized ? size : 0, now};
  return key;
}

std::uint64_t SceneCache::sourceBytes(const SceneSource& source) const {
  switch (source.kind) {
    case SceneSource::Kind::Builtin:
      return 0;
    case SceneSource::Kind::InlineGlb:
      return source.glbBytes.size();
    case SceneSource::Kind::UploadedGltf: {
      std::uint64_t bytes = 0;
      for (const auto& [name, file] : source.uploadedFiles) bytes += file.size();
      return bytes;
    }
    case SceneSource::Kind::AssetPath:
      try {
        assetKey(source.assetPath);  // stats the file, or reuses the last look
      } catch (const Error&) {
        return 0;
      }
      return assetKeys_.at(source.assetPath).bytes;
  }
  return 0;
}

namespace {

// Built-in scenes are made here; assets are parsed by the scene parser worker when there is one
// (untrusted bytes never parsed in this process), else here.
Scene loadScene(const RendererOptions& rendererOptions, worker::SceneWorkerPool* parsers,
                const SceneSource& source, const SceneLoadOptions& options,
                std::optional<worker::SceneWorkerPool::Turn> turn) {
  if (source.kind == SceneSource::Kind::Builtin) {
    return source.builtin == BuiltinScene::Atrium ? makeAtriumScene() : makeDemoScene();
  }
  SceneLoadLimits limits;
  limits.maxTriangles = rendererOptions.maxTriangles;
  limits.maxTextureSize = rendererOptions.maxTextureSize;
  limits.maxTextureBytes = rendererOptions.maxTextureBytes;
  if (parsers != nullptr) {
    const worker::LoadJob job{source, rendererOptions.assetRoot, limits, options};
    return turn ? parsers->load(job, std::move(*turn)) : parsers->load(job);
  }
  return loadSceneSource(source, rendererOptions.assetRoot, limits, options);
}

}  // namespace

TraceSceneSlot SceneCache::buildTraceAhead(const TraceBuilder& build, const Scene& scene) {
  // A large scene's structures are built when it is drawn: the look-ahead holds up to 64 scenes,
  // and their structures would hold GPU memory that the cache's budget does not see.
  if (scene.triangleCount() > kMaxTrianglesBuiltAhead) return {};
  try {
    return build(scene);
  } catch (const std::exception& error) {
    // The frame that draws the scene builds it again, and reports what fails then.
    spdlog::warn("scene cache: the acceleration structures of '{}' could not be built ahead: {}",
                 scene.name, error.what());
    return {};
  }
}

SceneCache::Parsed SceneCache::parse(const RendererOptions& rendererOptions,
                                     worker::SceneWorkerPool* parsers, const SceneSource& source,
                                     const SceneLoadOptions& options, ParserTurn turn) {
  const Stopwatch timer;
  Parsed parsed;
  parsed.entry = std::make_shared<CachedScene>();
  parsed.entry->scene = loadScene(rendererOptions, parsers, source, options, std::move(turn));
  parsed.loadMs = timer.elapsedMs();
  return parsed;
}

void SceneCache::uploadAhead(Parsed& parsed, gl::Worker& worker, const GpuSceneOptions& options,
                             std::atomic<std::size_t>& aheadBytes) {
  const std::size_t bytes = estimatedUploadBytes(parsed.entry->scene);
  std::size_t held = aheadBytes.load();
  do {
    if (held + bytes > kMaxBytesUploadedAhead) return;  // uploaded when drawn
  } while (!aheadBytes.compare_exchange_weak(held, held + bytes));
  AheadReservation reservation(&aheadBytes, bytes);
  const Stopwatch upload;
  try {
    const Scene& scene = parsed.entry->scene;
    GpuSceneOwner gpu(
        worker.run([&scene, &options] { return GpuScene::uploadShared(scene, options); })
            .get()
            .release(),
        GpuSceneDeleter(&worker));
    parsed.entry->gpu = std::move(gpu);
  } catch (const std::exception& error) {
    // The frame that draws the scene uploads it again, and reports what fails then.
    spdlog::warn("scene cache: '{}' could not be uploaded ahead: {}", parsed.entry->scene.name,
                 error.what());
    return;
  }
  parsed.uploadMs = upload.elapsedMs();
  parsed.uploadedAhead = std::move(reservation);
}

void SceneCache::stage(Parsed& parsed, gl::StagingMemory& staging, TextureCompression compression,
                       std::size_t minBytes) {
  try {
    parsed.staged = stageScene(parsed.entry->scene, staging, compression, minBytes);
  } catch (const std::exception& error) {  // no memory for its bookkeeping
    spdlog::warn("scene cache: '{}' could not be staged ({}): uploaded from its own memory",
                 parsed.entry->scene.name, error.what());
  }
}

std::size_t SceneCache::prefetchDepth() const {
  constexpr std::size_t kPerProcess = 8;
  constexpr std::size_t kMaxDepth = 64;
  constexpr std::size_t kInProcess = 2;
  return parsers_ ? std::min(kPerProcess * parsers_->maxProcesses(), kMaxDepth) : kInProcess;
}

void SceneCache::prefetch(const SceneSource& source, const SceneLoadOptions& options,
                          TraceBuilder buildTrace) {
  const std::uint64_t hint = hints_++;
  std::string key;
  try {
    key = keyFor(source, options);
  } catch (const Error&) {
    return;  // a bad path: get() reports it
  }
  if (key.empty() || key == "demo") return;
  // Drawn right after the same scene (the views of one asset): the cache's newest entry.
  if (key == lastHintKey_) return;
  lastHintKey_ = key;
  const bool keptWhenDrawn = options_.sceneCacheBytes > 0;
  if (keptWhenDrawn) {
    if (const auto pending = newestPrefetch(key); pending != prefetches_.end()) {
      // The same scene again within the look-ahead (a batch that repeats an asset): one parse
      // serves the first; get() starts the next where the cache will not keep the scene.
      pending->second.laterHints.push_back(hint);
      return;
    }
    for (const Slot& slot : slots_) {
      if (slot.key == key) return;
    }
  }
  // With the cache off every draw of a scene other than the newest is a parse of its own: each
  // hint starts one, as early as a new scene's (started when its first draw was, the repeat of an
  // asset 31 thumbnails later waited for its parse on the H200).
  if (prefetches_.size() >= maxPrefetches()) dropStalePrefetches();
  if (prefetches_.size() >= maxPrefetches()) {
    // No room: the draw of the scene before it starts this one's parse, as with the cache on.
    if (const auto pending = newestPrefetch(key); pending != prefetches_.end()) {
      pending->second.laterHints.push_back(hint);
    }
    return;
  }
  startPrefetch(key, std::make_shared<const SceneSource>(source), options, std::move(buildTrace),
                hint, {});
}

std::optional<bool> SceneCache::inProgress(const SceneSource& source,
                                           const SceneLoadOptions& options) const {
  if (source.kind == SceneSource::Kind::InlineGlb ||
      source.kind == SceneSource::Kind::UploadedGltf) {
    return std::nullopt;  // keyed by a hash of all its bytes: too dear to ask for on every look
  }
  std::string key;
  try {
    key = keyFor(source, options);
  } catch (const Error&) {
    return false;
  }
  if (key.empty() || key == "demo") return false;
  for (const Slot& slot : slots_) {
    if (slot.key == key) return false;
  }
  const auto oldest = prefetches_.lower_bound(key);
  if (oldest == prefetches_.end() || oldest->first != key) return false;
  return oldest->second.parsed.wait_for(std::chrono::seconds(0)) != std::future_status::ready;
}

void SceneCache::dropStalePrefetches() {
  const std::uint64_t horizon = 2 * maxPrefetches();
  std::erase_if(prefetches_, [&](const auto& entry) {
    const Prefetch& prefetch = entry.second;
    return prefetch.hint + horizon < hints_ &&
           prefetch.parsed.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
  });
}

std::multimap<std::string, SceneCache::Prefetch>::iterator SceneCache::oldestPrefetch(
    const std::string& key) {
  const auto first = prefetches_.lower_bound(key);
  return first != prefetches_.end() && first->first == key ? first : prefetches_.end();
}

std::multimap<std::string, SceneCache::Prefetch>::iterator SceneCache::newestPrefetch(
    const std::string& key) {
  const auto [first, last] = prefetches_.equal_range(key);
  return first == last ? prefetches_.end() : std::prev(last);
}

void SceneCache::startPrefetch(const std::string& key, std::shared_ptr<const SceneSource> source,
                               const SceneLoadOptions& options, TraceBuilder buildTrace,
                               std::uint64_t hint, std::deque<std::uint64_t> laterHints) {
  auto entry = prefetches_.end();
  try {
    if (!prefetchThreads_) {
      prefetchThreads_ =
          std::make_unique<TaskPool>(static_cast<int>(maxPrefetches()), "lgh-prefetch");
    }
    // The parsers serve it in hint order, whenever its thread gets to them.
    ParserTurn turn;
    if (parsers_) turn.emplace(parsers_->reserveTurn());
    // On the GL worker (which is when this is used): no recycled textures.
    const GpuSceneOptions uploadOptions{maxAnisotropy_, options.textureCompression,
                                        textureCapabilities_, nullptr, nullptr};
    auto parsing = std::make_shared<std::packaged_task<Parsed()>>(
        [rendererOptions = options_, parsers = parsers_.get(), source, options, buildTrace,
         turn = std::move(turn), glWorker = glWorker_.get(), uploadOptions,
         aheadBytes = &uploadedAheadBytes_, staging = staging_.get()]() mutable {
          Parsed parsed = parse(rendererOptions, parsers, *source, options, std::move(turn));
          if (glWorker != nullptr) uploadAhead(parsed, *glWorker, uploadOptions, *aheadBytes);
          // Off the render thread, which on a CPU rasteriser would build them while it uploads.
          if (glWorker == nullptr && uploadOptions.capabilities &&
              uploadOptions.capabilities->mipmapsOnCpu &&
              options.textureCompression == TextureCompression::None) {
            parsed.mipChains = buildSceneMipChains(parsed.entry->scene);
          }
          if (staging != nullptr) {
            stage(parsed, *staging, options.textureCompression,
                  rendererOptions.uploadStagingMinBytes);
          }
          if (buildTrace) {
            const Stopwatch build;
            parsed.entry->trace = buildTraceAhead(buildTrace, parsed.entry->scene);
            if (parsed.entry->trace.scene) parsed.buildMs = build.elapsedMs();
          }
          return parsed;
        });
    // After the other hints of the key: get() takes them in hint order.
    entry = prefetches_.emplace(key, Prefetch{parsing->get_future(), std::move(source), options,
                                              std::move(buildTrace), hint, std::move(laterHints)});
    prefetchThreads_->submit([parsing] { (*parsing)(); });  // its exceptions go to the future
  } catch (const std::exception& error) {  // no thread (std::system_error), no memory
    spdlog::warn("scene cache: no thread for a prefetch ({}); the scene is parsed when drawn",
                 error.what());
    if (entry != prefetches_.end()) prefetches_.erase(entry);
  }
}

SceneCache::Lookup SceneCache::get(const SceneSource& source, const SceneLoadOptions& options) {
  Lookup lookup;
  if (staging_) staging_->reclaim();
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
  Parsed parsed;
  std::optional<Prefetch> next;  // for the same scene hinted again behind this one
  if (auto pending = oldestPrefetch(key); pending != prefetches_.end()) {
    std::future<Parsed> parsing = std::move(pending->second.parsed);
    if (!pending->second.laterHints.empty()) next = std::move(pending->second);
    prefetches_.erase(pending);
    const Stopwatch wait;
    parsed = parsing.get();  // rethrows the parse's error
    lookup.prefetched = true;
    // What the thumbnail benchmarks' "scene wait" is made of (--log-level debug).
    if (const double waitedMs = wait.elapsedMs(); waitedMs >= 1.0) {
      spdlog::debug(
          "scene cache: waited {:.2f} ms for the prefetched parse of {} (parse {:.2f} ms{})",
          waitedMs, key, parsed.loadMs,
          parsed.buildMs >= 0.0
              ? fmt::format(", structures built ahead in {:.2f} ms", parsed.buildMs)
              : std::string());
    }
  } else {
    parsed = parse(options_, parsers_.get(), source, options);
    if (parsers_) {
      spdlog::debug("scene cache: {} was not prefetched: parsed while drawing ({:.2f} ms)", key,
                    parsed.loadMs);
    }
  }
  std::shared_ptr<CachedScene> entry = std::move(parsed.entry);
  lookup.loadMs = parsed.loadMs;
  const Stopwatch uploadTimer;
  if (entry->gpu) {
    entry->gpu->adopt();
    lookup.uploadedAhead = true;
    lookup.uploadAheadMs = parsed.uploadMs;
  } else {
    const StagedScene* staged = parsed.staged ? &*parsed.staged : nullptr;
    try {
      entry->gpu = GpuSceneOwner(
          new GpuScene(  // NOLINT(cppcoreguidelines-owning-memory): owned at once
              entry->scene,
              GpuSceneOptions{maxAnisotropy_, options.textureCompression, textureCapabilities_,
                              recycledTextures_, recycledBuffers_},
              staged, &parsed.mipChains),
          GpuSceneDeleter(glWorker_.get()));
    } catch (...) {
      // Copies from the region may have been issued before the failure.
      if (staged != nullptr) staging_->retire(std::move(parsed.staged->region));
      throw;
    }
    if (staged != nullptr) {
      staging_->retire(std::move(parsed.staged->region));
      lookup.staged = true;
    }
  }
  lookup.uploadMs = uploadTimer.elapsedMs();
  lookup.entry = entry;
  slots_.push_front({key, entry});
  const Stopwatch release;
  evictOverBudget();
  lookup.releaseMs = release.elapsedMs();
  // Kept only as the most recent scene (over the budget: with the cache off, always), the scene
  // is gone before its later hint is drawn: that one gets a parse of its own.
  if (next && stats().bytes > options_.sceneCacheBytes) {
    const std::uint64_t hint = next->laterHints.front();
    next->laterHints.pop_front();
    startPrefetch(key, next->source, next->options, std::move(next->buildTrace), hint,
                  std::move(next->laterHints));
  }
  return lookup;
}

void SceneCache::evictOverBudget() {
  std::size_t total = 0;
  for (const Slot& slot : slots_) total += slot.entry->gpuBytes();
  while (slots_.size() > 1 && total > options_.sceneCacheBytes) {
    const std::size_t bytes = slots_.back().entry->gpuBytes();
    spdlog::info("scene cache: evicting {} ({} bytes)", slots_.back().key, bytes);
    total -= bytes;
    Slot evicted = std::move(slots_.back());
    slots_.pop_back();
    release(std::move(evicted));
  }
}

// Frees an evicted scene part by part, so that the debug log says what its release costs the
// render thread (the `scene release` row is their sum).
void SceneCache::release(Slot evicted) {
  if (evicted.entry.use_count() != 1) return;  // still held by a caller: freed with it
  CachedScene& scene = *evicted.entry;
  if (glWorker_) {
    // Vertex arrays belong to this context; the rest is freed on the worker. The flush sends
    // this context's commands that use the scene before another context deletes its objects.
    const Stopwatch here;
    scene.gpu->releaseVertexArrays();
    glFlush();
    glWorker_->post([entry = std::move(evicted.entry)]() mutable { entry.reset(); });
    spdlog::debug("scene cache: released {} on the GL worker ({:.3f} ms here)", evicted.key,
                  here.elapsedMs());
    return;
  }
  const Stopwatch gl;
  scene.gpu.reset();
  scene.hitGeometry.reset();
  const double glMs = gl.elapsedMs();
  const Stopwatch structures;
  releaseStructures(std::move(scene.trace.scene));
  const double structuresMs = structures.elapsedMs();
  const Stopwatch cpu;
  evicted.entry.reset();
  spdlog::debug(
      "scene cache: released {}: GL objects {:.3f} ms, acceleration structures {:.3f} ms, "
      "CPU memory {:.3f} ms",
      evicted.key, glMs, structuresMs, cpu.elapsedMs());
}

// Destroying a scene's acceleration structures is a deferred-release submission and the frees
// of their buffers: no frame waits for it, so a thread of its own does it (Vulkan's queues are
// submitted to under their locks, DeferredRelease has its own).
void SceneCache::releaseStructures(std::unique_ptr<vk::TraceScene> structures) {
  if (!structures) return;
  try {
    if (!structureReleaser_) structureReleaser_ = std::make_unique<TaskPool>(1, "lgh-as-free");
    structureReleaser_->submit([held = std::shared_ptr<vk::TraceScene>(
                                    std::move(structures))]() mutable { held.reset(); });
  } catch (const std::exception& error) {  // no thread (std::system_error), no memory
    spdlog::warn("scene cache: acceleration structures freed on the render thread ({})",
                 error.what());
    structures.reset();
  }
}

SceneCacheStats SceneCache::stats() const {
  SceneCacheStats stats;
  stats.hits = hits_;
  stats.misses = misses_;
  stats.entries = slots_.size();
  for (const Slot& slot : slots_) stats.bytes += slot.entry->gpuBytes();
  stats.stagingBytes = stagingBytes();
  stats.stagingBytesInUse = stagingBytesInUse();
  if (recycledTextures_) {
    const auto textures = recycledTextures_->stats();
    stats.recycledTextures = textures.recycled;
    stats.keptStorageBytes += textures.keptBytes;
  }
  if (recycledBuffers_) {
    const auto buffers = recycledBuffers_->stats();
    stats.recycledBuffers = buffers.recycled;
    stats.keptStorageBytes += buffers.keptBytes;
  }
  return stats;
}

}  // namespace lgh
