// The renderer's public API: a Renderer owns one headless GL context and turns a validated
// RenderRequest into an image (its pixels as the GPU wrote them, and their encoding) plus a timing
// table. The daemon, the CLI and the benchmark are thin clients of this header; none of them sees
// GL. Nothing inside the library includes it: the types it trades in live in vocabulary headers
// of their own.
//
// Frames in flight (docs/ARCHITECTURE.md): submit() issues a frame's GPU work and the copy of its
// pixels into read-back memory, and returns without waiting for the GPU; finish() hands the
// oldest frame over once its fence has signalled. The pixels are then read where the GPU put
// them, on any thread (encode them on a TaskPool), and go back to the renderer when the last
// FramePixels holding them is released. render() is submit() + finish() + encode in one call.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "lgh/device_info.hpp"
#include "lgh/render_result.hpp"
#include "lgh/renderer_options.hpp"
#include "lgh/request.hpp"
#include "lgh/resource_stats.hpp"
#include "lgh/scene_cache_stats.hpp"
#include "lgh/shadow_info.hpp"

namespace lgh {

class Renderer {
 public:
  // Creates the GL context on the calling thread; that thread must make every later call.
  explicit Renderer(const RendererOptions& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders and encodes on this thread. Throws lgh::Error: NotFound/Invalid/TooLarge for bad
  // scenes, Internal for GL failures. Frames submitted earlier stay pending.
  RenderResult render(const RenderRequest& request);
  // The same frame without its encoding (`encoded` stays empty, no "encode" row): for callers
  // that encode elsewhere (RenderResult::encode is safe on any thread) or not at all.
  RenderResult renderFrame(const RenderRequest& request);

  // Issues the frame (scene lookup and upload, passes, the read-back copy) and returns its id
  // without waiting for the GPU. With options().framesInFlight frames pending, it first waits for
  // the oldest one's read-back (that frame stays pending for finish()). Throws as render() does;
  // a frame that throws is not pending.
  std::uint64_t submit(const RenderRequest& request);
  // The oldest pending frame, once its pixels are read back (`encoded` empty: encode it with
  // RenderResult::encode, anywhere). Without `wait`, nullopt while it is still on the GPU; nullopt
  // when none is pending. Without `wait` nothing is waited for: a split frame (docs/SHADOWS.md,
  // "Overlapped frames") whose rays are still being traced stays for the next submit() or a later
  // call. Throws lgh::Error(Internal) when the GPU cannot be waited for.
  std::optional<RenderResult> finish(bool wait);
  std::size_t pendingFrames() const;

  // A hint that `request` comes next: its scene is parsed on a thread of its own meanwhile,
  // unless it is cached (the GL upload waits for the submit). Errors surface from that submit.
  void prefetch(const RenderRequest& request);
  // Whether `request`'s scene is still being parsed ahead (with its acceleration structures) for
  // a prefetch() hint: a submit() of it now would wait for that. A caller with several requests
  // to draw can draw one whose scene is at hand first. nullopt for an uploaded scene (glTF or
  // GLB bytes in the request), which is not looked up: its key is a hash of all its bytes.
  std::optional<bool> scenePending(const RenderRequest& request) const;
  // The bytes `request`'s scene is parsed from (an asset file's size, an upload's bytes; 0 for a
  // built-in scene): a guess at its parse's cost, for a caller that orders its prefetch() hints.
  std::uint64_t sceneSourceBytes(const RenderRequest& request) const;
  // How many of the requests to come are worth a prefetch() hint: as many as scenes parse side
  // by side (RendererOptions::sceneWorker.processes, 1 without a parser worker).
  std::size_t prefetchDepth() const;

  // Read-back memory: buffers held by frames (pending, or finished and not yet released) and all
  // buffers the renderer keeps. Safe on any thread.
  struct ReadbackStats {
    std::size_t heldBuffers = 0;
    std::size_t heldBytes = 0;
    std::size_t pooledBuffers = 0;
    std::size_t pooledBytes = 0;
  };
  ReadbackStats readbackStats() const;

  const DeviceInfo& device() const;
  const RendererOptions& options() const;

  using CacheStats = SceneCacheStats;
  CacheStats sceneCacheStats() const;

  // The shadow side: its Vulkan device and paths, or why there is none.
  ShadowInfo shadowInfo() const;

  // Live GL objects and GPU memory (queries the GL context: call it on the render thread).
  ResourceStats resourceStats() const;

  // False once the GL context was lost (a GPU reset reported through GL_KHR_robustness): every
  // later render fails with Unavailable; make a new Renderer. The environment variable
  // LGH_DEBUG_CONTEXT_LOSS_AFTER=N (a test hook) reports a loss after N frames.
  bool healthy() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace lgh
