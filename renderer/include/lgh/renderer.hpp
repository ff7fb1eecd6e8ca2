// The renderer's public API: a Renderer owns one headless GL context and turns a validated
// RenderRequest into a linear image plus a timing table. The daemon, the CLI and the benchmark are
// thin clients of this header; none of them sees GL. Nothing inside the library includes it: the
// types it trades in live in vocabulary headers of their own.
#pragma once

#include <memory>

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

  // Throws lgh::Error: NotFound/Invalid/TooLarge for bad scenes, Internal for GL failures.
  RenderResult render(const RenderRequest& request);
  // The same frame without its encoding (`encoded` stays empty, no "encode" row): for callers
  // that encode elsewhere (RenderResult::encode is safe on any thread) or not at all.
  RenderResult renderFrame(const RenderRequest& request);

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
