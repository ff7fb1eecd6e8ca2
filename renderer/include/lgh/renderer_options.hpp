// How a Renderer is set up: which context path, which GPU, which limits. A vocabulary header: the
// context and the scene cache read it without seeing the Renderer façade.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "lgh/enum_names.hpp"

namespace lgh {

enum class ContextBackend { Auto, EglDevice, Surfaceless, OSMesa };

// The scene parser worker process: started as `executable arguments...` with its end of a socket
// on file descriptor 3, where the program must call lgh::runSceneParserWorker(3). One worker,
// started with the renderer and restarted after it dies.
struct SceneWorkerOptions {
  std::filesystem::path executable;  // empty: no worker, parse in the renderer's process
  std::vector<std::string> arguments;
  std::size_t memoryBytes = 4ULL << 30;  // its data size limit (RLIMIT_DATA): past it, 413
  double timeoutSeconds = 120.0;         // one load; past it the worker is killed: 413
  // Parser processes at most (each with the memory limit above): the scenes a render thread
  // draws next parse side by side. More start only while every running one is busy.
  std::size_t processes = 1;
  // Each worker's answers are written into this much shared memory, kept for the worker's life
  // (its pages stay resident once an answer used them); a larger answer, or every answer with 0,
  // comes in memory of its own, made and unmapped per answer.
  std::size_t answerArenaBytes = std::size_t{16} << 20;
};

template <>
struct EnumNames<ContextBackend> {
  static constexpr std::array<EnumName<ContextBackend>, 4> names{{
      {"auto", ContextBackend::Auto},
      {"egl-device", ContextBackend::EglDevice},
      {"surfaceless", ContextBackend::Surfaceless},
      {"osmesa", ContextBackend::OSMesa},
  }};
};

// "auto", "egl-device", "surfaceless", "osmesa"; throws lgh::Error(BadRequest) otherwise.
ContextBackend parseContextBackend(const std::string& name);
const char* contextBackendName(ContextBackend backend);

struct RendererOptions {
  ContextBackend backend = ContextBackend::Auto;
  int gpuIndex = 0;         // EGL device index (EGL's order, not CUDA's)
  bool requireGpu = false;  // fail instead of running on a software rasterizer
  bool glDebug = false;     // KHR_debug context; messages go to the log either way
  std::filesystem::path assetRoot = ".";
  std::size_t maxTriangles = 20'000'000;
  int maxTextureSize = 16384;
  std::size_t maxTextureBytes = 4ULL << 30;    // all textures of one scene, decoded to RGBA8
  std::size_t sceneCacheBytes = 512ULL << 20;  // GPU memory budget of the scene cache
  // Frames whose GPU work and read-back may be under way at once (Renderer::submit): the GPU
  // works on frame N while the CPU issues frames N + 1 and on. A shadowed frame's hand-overs
  // between GL and Vulkan make its latency several times its GPU time (docs/BENCHMARKS.md,
  // "GPU targets, fourth and fifth rounds"): with 2, and then with 4 once it issued them faster,
  // a render thread issuing small frames waited for them.
  int framesInFlight = 8;
  // A shadowed frame's last passes (direct lighting, composite, read-back copy) are issued after
  // the next frame's G-buffer and ray set-up, so that GL draws that frame while Vulkan traces
  // this one's rays instead of waiting for them (docs/SHADOWS.md, "Overlapped frames"). A frame
  // left so is finished by the next submit(), or when it is waited for or polled as the oldest.
  bool overlapShadowedFrames = true;
  // A second GL context in the render context's share group, current on a thread of its own
  // (the GL worker): scenes parsed ahead are uploaded there, and evicted scenes freed there, off
  // the render thread (docs/ARCHITECTURE.md, "GL worker"). Off by default: on the H200 the
  // render thread's GL calls slowed while the worker uploaded (docs/BENCHMARKS.md, seventh
  // round), more than the upload it took over. A driver without shared contexts is logged.
  bool glWorker = false;
  // Persistently mapped memory that prefetch threads copy parsed scenes' vertices, indices and
  // decoded pixels into, so that the render thread uploads them as GPU copies instead of copying
  // the bytes itself (docs/ARCHITECTURE.md, "Upload staging"). -1: 128 MiB on a GPU, none on a
  // software rasterizer (whose GPU copy is a CPU copy too) or with the GL worker; 0: none. A
  // scene that finds no room when parsed is uploaded from its own memory.
  std::int64_t uploadStagingBytes = -1;
  // Scenes smaller than this are uploaded from their own memory even with staging: on the H200 a
  // scene uploaded by GPU copies cost its first draws about 0.4 ms more whatever its size (the
  // G-buffer pass's issue), which only scenes of about a megabyte or more win back
  // (docs/BENCHMARKS.md, eighth round).
  std::size_t uploadStagingMinBytes = std::size_t{1} << 20;
  // Untrusted assets (paths, uploads, inline GLBs) parsed in a worker process
  // (lgh/scene_worker.hpp) rather than in this one: a parser crash or runaway then fails one load,
  // not the process. Empty executable: in this process.
  SceneWorkerOptions sceneWorker;
  // FOR TESTS ONLY: report a lost context after this many frames, as a GPU reset would (-1: as
  // LGH_DEBUG_CONTEXT_LOSS_AFTER says, else never). One renderer of several can be made to fail.
  int debugContextLossAfter = -1;
};

}  // namespace lgh
