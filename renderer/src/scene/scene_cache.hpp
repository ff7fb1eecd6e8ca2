// LRU cache of loaded scenes (CPU data + GPU upload + acceleration structures) keyed by content:
// "demo", an asset's resolved path + size + mtime, or a hash of inline GLB bytes. Bounded by a GPU
// memory budget, checked on every lookup; the most recently used scene is always kept, even when
// it alone exceeds the budget.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>

#include "gl/gl_worker.hpp"
#include "gl/staging_memory.hpp"
#include "lgh/renderer_options.hpp"
#include "lgh/scene_cache_stats.hpp"
#include "lgh/task_pool.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/gpu_scene.hpp"
#include "scene/scene.hpp"
#include "scene/scene_mip_chains.hpp"
#include "scene/staged_scene.hpp"
#include "scene/worker/scene_worker_pool.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh {

// The acceleration structures of a cached scene, built by the first shadowed frame that draws it
// and kept while the tracer that built them lives (`epoch`: ShadowDevice::epoch()).
struct TraceSceneSlot {
  std::unique_ptr<vk::TraceScene> scene;
  std::uint64_t epoch = 0;
};

// GPU data that another part of the renderer derives from a cached scene and keeps with it (the
// triangles and materials that GI resolves ray hits with, gi/hit_geometry.hpp): built by the
// first frame that needs it, freed with the scene, counted against the cache's budget.
class SceneAttachment {
 public:
  virtual ~SceneAttachment() = default;
  virtual std::size_t gpuBytes() const = 0;
};

// Frees a GpuScene where its GL objects may be deleted: at once on a thread whose current context
// is in the render context's share group, else (a prefetch thread dropping a scene uploaded
// ahead) on the GL worker. A scene with vertex arrays is only ever freed on the render thread.
struct GpuSceneDeleter {
  gl::Worker* worker = nullptr;  // none: always at once
  GpuSceneDeleter() = default;
  explicit GpuSceneDeleter(gl::Worker* glWorker) : worker(glWorker) {}
  // NOLINTNEXTLINE(google-explicit-constructor): a std::unique_ptr<GpuScene> converts to it.
  GpuSceneDeleter(std::default_delete<GpuScene> /*plain*/) {}
  void operator()(GpuScene* scene) const;
};
using GpuSceneOwner = std::unique_ptr<GpuScene, GpuSceneDeleter>;

struct CachedScene {
  Scene scene;
  GpuSceneOwner gpu;
  // Built lazily, by frames that hold the entry as const: part of the cache, not of the scene.
  mutable TraceSceneSlot trace;
  mutable std::unique_ptr<SceneAttachment> hitGeometry;

  // GPU memory held: the GL upload, the acceleration structures and the hit geometry.
  std::size_t gpuBytes() const {
    return gpu->gpuBytes() + (trace.scene ? trace.scene->gpuBytes() : 0) +
           (hitGeometry ? hitGeometry->gpuBytes() : 0);
  }
};

class SceneCache {
 public:
  // `context`: the render context, whose share group the GL worker joins (RendererOptions::
  // glWorker); without one, uploads and releases stay on the calling thread.
  explicit SceneCache(const RendererOptions& options, const GlContext* context = nullptr);
  ~SceneCache();
  SceneCache(const SceneCache&) = delete;
  SceneCache& operator=(const SceneCache&) = delete;

  struct Lookup {
    std::shared_ptr<CachedScene> entry;
    bool hit = false;
    double loadMs = 0.0;         // parsing, here or on a prefetch thread
    double uploadMs = 0.0;       // on the calling thread (after an upload ahead: its adoption)
    bool uploadedAhead = false;  // on the GL worker, ahead of this get()
    double uploadAheadMs = 0.0;  // that upload's wall time
    double releaseMs = 0.0;      // freeing the scenes this miss evicted (GL, Vulkan and CPU memory)
    bool prefetched = false;     // parsed by prefetch() ahead of this get()
    bool staged = false;         // uploaded by GPU copies from staging memory
  };
  // Loads on a miss; throws lgh::Error for bad assets (nothing is cached then). The options (pose,
  // material variant, extension tolerance) are part of the key: each pose is its own entry.
  Lookup get(const SceneSource& source, const SceneLoadOptions& options = {});
  SceneCacheStats stats() const;

  // Builds a parsed scene's acceleration structures on the prefetch thread (ShadowDevice::
  // prefetchBuilder); an empty slot leaves the build to the frame that draws the scene.
  using TraceBuilder = std::function<TraceSceneSlot(const Scene&)>;
  // Starts parsing `source` on a prefetch thread unless it is cached or already being parsed;
  // the get() that asks for it then waits for that parse instead of parsing (its errors come
  // from that get()). With `buildTrace`, the same thread then builds the scene's acceleration
  // structures. The upload stays for get(), on the GL thread. At most maxPrefetches() parses
  // run at once; a hint beyond that is dropped. Hints come in the requests' order (a caller may
  // draw a later one first while an earlier one is inProgress): a hint of the key hinted just
  // before is the cache's newest scene when drawn, and is not parsed; with the cache
  // off (a budget of 0) every other hint of a scene starts a parse of its own.
  void prefetch(const SceneSource& source, const SceneLoadOptions& options = {},
                TraceBuilder buildTrace = {});
  // Whether the scene is being prefetched still: not cached, and its oldest prefetch (parse and
  // structures built ahead) not done. get() would wait for it; once done, or for a scene that is
  // cached, never hinted or cannot be keyed, get() would not wait for a prefetch. Lets the caller
  // draw a later request first (lghd's render worker). nullopt for an uploaded scene, which is
  // not looked up: its key is a hash of all its bytes, too dear to compute on every look.
  std::optional<bool> inProgress(const SceneSource& source,
                                 const SceneLoadOptions& options = {}) const;
  // The bytes `source` is parsed from: an asset file's size (a .gltf's own, without the side
  // files it names), an uploaded or inline scene's bytes; 0 for a built-in scene or a path that
  // does not resolve (get() reports that). A cheap guess at the parse's cost.
  std::uint64_t sourceBytes(const SceneSource& source) const;
  // Scenes hinted ahead: eight per parser process (2 without them, parsed side by side on this
  // process's prefetch threads), at most 64, so that the
  // look-ahead covers a slow asset's parse (a draco or textured asset took 20-56 ms to parse on
  // the H200 machine while small ones drew in 1-2.5 ms each: with three hints per process the
  // render thread still waited 0.7 ms per thumbnail for them). Beyond the processes, parses wait
  // in hint order for a free one. Prefetches run at most one more than the depth.
  std::size_t prefetchDepth() const;
  std::size_t maxPrefetches() const { return prefetchDepth() + 1; }
  // Parses started by prefetch() that no get() has taken yet.
  std::size_t pendingPrefetches() const { return prefetches_.size(); }

  // Content key of a source ("" when it cannot be keyed; then it is never cached).
  std::string keyFor(const SceneSource& source, const SceneLoadOptions& options = {}) const;
  // Whether scenes are uploaded ahead and freed on a GL worker (RendererOptions::glWorker).
  bool hasGlWorker() const { return glWorker_ != nullptr; }
  // The staging memory's size (0: none) and its bytes held by scenes parsed, not yet uploaded.
  std::size_t stagingBytes() const { return staging_ ? staging_->capacity() : 0; }
  std::size_t stagingBytesInUse() const { return staging_ ? staging_->bytesInUse() : 0; }

  // Scenes parsed ahead are uploaded ahead while the GPU memory of those not drawn yet stays
  // under this (their bytes are not in the cache's budget until drawn); a scene that does not
  // fit is uploaded when drawn.
  static constexpr std::size_t kMaxBytesUploadedAhead = std::size_t{256} << 20;

 private:
  // GPU memory held by uploads ahead not drawn yet: reserved before an upload ahead, given back
  // when the scene is drawn or its parse dropped.
  class AheadReservation {
   public:
    AheadReservation() = default;
    AheadReservation(std::atomic<std::size_t>* total, std::size_t bytes)
        : total_(total), bytes_(bytes) {}
    ~AheadReservation() { reset(); }
    AheadReservation(AheadReservation&& other) noexcept
        : total_(std::exchange(other.total_, nullptr)), bytes_(other.bytes_) {}
    AheadReservation& operator=(AheadReservation&& other) noexcept {
      if (this != &other) {
        reset();
        total_ = std::exchange(other.total_, nullptr);
        bytes_ = other.bytes_;
      }
      return *this;
    }
    AheadReservation(const AheadReservation&) = delete;
    AheadReservation& operator=(const AheadReservation&) = delete;
    void reset() {
      if (total_ != nullptr) total_->fetch_sub(bytes_);
      total_ = nullptr;
    }

   private:
    std::atomic<std::size_t>* total_ = nullptr;
    std::size_t bytes_ = 0;
  };
  struct Parsed {
    std::shared_ptr<CachedScene> entry;  // the scene, its structures and upload when made ahead
    double loadMs = 0.0;
    double buildMs = -1.0;   // the build ahead's wall time (< 0: none)
    double uploadMs = -1.0;  // the upload ahead's wall time on the GL worker (< 0: none)
    AheadReservation uploadedAhead;
    std::optional<StagedScene> staged;  // its bytes in staging memory (none: no room, or off)
    SceneMipChains mipChains;  // a CPU rasteriser's texture levels, built on the prefetch thread
  };
  // On a prefetch thread: the parsed scene's upload on the GL worker, when its bytes fit.
  static void uploadAhead(Parsed& parsed, gl::Worker& worker, const GpuSceneOptions& options,
                          std::atomic<std::size_t>& aheadBytes);
  // On a prefetch thread: the parsed scene's bytes copied into staging memory, when they fit.
  static void stage(Parsed& parsed, gl::StagingMemory& staging, TextureCompression compression,
                    std::size_t minBytes);
  static constexpr std::size_t kMaxTrianglesBuiltAhead = 250'000;
  static TraceSceneSlot buildTraceAhead(const TraceBuilder& build, const Scene& scene);
  // In the scene parser worker when there is one (untrusted bytes never parsed here), in its
  // turn: `turn`, taken when the scene was hinted, or one taken now.
  using ParserTurn = std::optional<worker::SceneWorkerPool::Turn>;
  static Parsed parse(const RendererOptions& rendererOptions, worker::SceneWorkerPool* parsers,
                      const SceneSource& source, const SceneLoadOptions& options,
                      ParserTurn turn = std::nullopt);
  std::string sourceKey(const SceneSource& source) const;
  // An asset path's key: resolved inside the asset root and stat'ed (some twenty system calls),
  // then reused for kAssetKeyLifetime: the hint and the draw of one thumbnail, and the repeats of
  // an asset in a batch, ask for it within milliseconds. A file changed on disk is seen by the
  // requests drawn from kAssetKeyLifetime after the change on.
  std::string assetKey(const std::string& assetPath) const;
  static constexpr std::chrono::milliseconds kAssetKeyLifetime{500};
  static constexpr std::size_t kMaxAssetKeys = 4096;
  struct AssetKey {
    std::string key;
    std::uintmax_t bytes = 0;  // the file's size
    std::chrono::steady_clock::time_point checked;
  };
  mutable std::unordered_map<std::string, AssetKey> assetKeys_;
  void evictOverBudget();
  RendererOptions options_;
  // Declared first: freed last, after every scene that may hand it work.
  std::unique_ptr<gl::Worker> glWorker_;
  // The RGBA8 textures' and geometry buffers' storage of scenes freed on the render thread, for
  // later scenes (none with a GL worker, which frees scenes on its own thread).
  std::shared_ptr<gl::RecycledTextures> recycledTextures_;
  std::shared_ptr<gl::RecycledBuffers> recycledBuffers_;
  std::atomic<std::size_t> uploadedAheadBytes_{0};
  // Where prefetch threads copy the scenes they parsed (RendererOptions::uploadStagingBytes).
  // Declared before the prefetches, whose regions go back to it when they are dropped.
  std::unique_ptr<gl::StagingMemory> staging_;
  // Frees evicted scenes' acceleration structures without the GL worker: made on the first.
  std::unique_ptr<TaskPool> structureReleaser_;
  std::unique_ptr<worker::SceneWorkerPool> parsers_;
  // A parse started by prefetch(); `hint`: its hint's number (prefetch() calls so far, the
  // position of its draw in the look-ahead); `laterHints`: the numbers of later hints of the same
  // key that it serves or whose parse starts when it is drawn.
  struct Prefetch {
    std::future<Parsed> parsed;
    std::shared_ptr<const SceneSource> source;  // shared with the parse's task: one copy
    SceneLoadOptions options;
    TraceBuilder buildTrace;
    std::uint64_t hint = 0;
    std::deque<std::uint64_t> laterHints;
  };
  void startPrefetch(const std::string& key, std::shared_ptr<const SceneSource> source,
                     const SceneLoadOptions& options, TraceBuilder buildTrace, std::uint64_t hint,
                     std::deque<std::uint64_t> laterHints);
  // Finished parses whose draw has passed (a cancelled request's, a failed ticket's): their
  // hints are more than twice the look-ahead old.
  void dropStalePrefetches();
  // By key, several of a key in hint order (with the cache off, one per draw to come).
  // Declared after parsers_ so that its parses (which may use them) end first.
  std::multimap<std::string, Prefetch> prefetches_;
  std::multimap<std::string, Prefetch>::iterator oldestPrefetch(const std::string& key);
  std::multimap<std::string, Prefetch>::iterator newestPrefetch(const std::string& key);
  std::string lastHintKey_;
  std::uint64_t hints_ = 0;  // prefetch() calls so far
  // The threads that wait for the prefetched parses, made on the first hint and kept: a thread
  // made per hint cost the render thread a clone() per new scene. Declared after parsers_ and
  // prefetches_: joined before they go.
  std::unique_ptr<TaskPool> prefetchThreads_;
  float maxAnisotropy_ = 1.0F;
  TextureCapabilities textureCapabilities_;
  struct Slot {
    std::string key;
    std::shared_ptr<CachedScene> entry;
  };
  void release(Slot evicted);
  void releaseStructures(std::unique_ptr<vk::TraceScene> structures);
  std::list<Slot> slots_;  // front: most recently used
  std::uint64_t hits_ = 0;
  std::uint64_t misses_ = 0;
};

}  // namespace lgh
