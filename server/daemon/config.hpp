// lghd's configuration: command-line flags, each with a matching LGHD_* environment variable
// (a flag given on the command line wins over its variable). Defaults are safe for a public
// render service: loopback only, bounded bodies, images, scenes, batches and queue.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "lgh/renderer.hpp"
#include "lgh/request.hpp"

namespace lghd {

struct Limits {
  std::size_t maxBodyBytes = 64ULL << 20;
  int maxWidth = 4096;
  int maxHeight = 4096;
  std::int64_t maxPixels = 4096LL * 4096LL;
  int maxLights = 4096;
  int maxVpls = 1 << 20;
  std::size_t maxTriangles = 5'000'000;
  int maxTextureSize = 8192;
  std::size_t maxTextureMb = 2048;  // all textures of one scene, decoded
  int maxBatch = 64;
};

// Jobs for long work (POST /v1/jobs, jobs.hpp). Each render of a job gets `renderDeadline`
// instead of --deadline-seconds; the other limits are those of synchronous requests.
struct JobLimits {
  int maxJobs = 64;  // held at once: queued, running, or finished and not yet expired
  std::size_t memoryBytes = 1024ULL << 20;  // results held plus reservations of unfinished jobs
  std::chrono::seconds ttl{600};            // how long a finished job's status and result stay
  int maxBatch = 4096;  // thumbnails (assets x views) or benchmark renders in one job
  std::chrono::milliseconds renderDeadline{600'000};
};

// The output pipeline (docs/DAEMON.md, "Frames in flight"): encoder threads, and how many frames
// (and bytes of their pixels) may be between submission and the end of their encoding.
struct OutputOptions {
  int encodeThreads = 0;   // 0: one per hardware thread
  int framesInFlight = 0;  // 0: twice the encoder threads
  std::size_t readbackBytes = 512ULL << 20;

  int encoderCount() const;
  std::size_t frameLimit() const;
};

struct DaemonConfig {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: any free port (printed on stdout)
  int httpThreads = 32;
  std::string authToken;  // empty: no authentication
  int queueDepth = 16;
  std::chrono::milliseconds deadline{30'000};
  std::chrono::milliseconds grace{10'000};
  std::chrono::milliseconds watchdog{60'000};  // past a render's deadline; 0: off
  std::size_t sceneCacheBytes = 512ULL << 20;
  std::string logFormat = "json";  // json | text
  std::chrono::milliseconds testRenderDelay{0};
  OutputOptions output;
  // A second port serving GET /metrics (and the probes) without the bearer token, for scrapers
  // that carry none (Prometheus' Kubernetes annotations). -1: none.
  int metricsPort = -1;
  // Untrusted assets parsed in a worker process (lgh::SceneWorkerOptions); the executable is
  // this one, started with kSceneWorkerFlag.
  bool sceneWorker = true;
  std::size_t sceneWorkerMemoryMb = 4096;
  double sceneWorkerTimeoutSeconds = 120.0;
  int sceneParsers = 0;  // parser processes per render worker; 0: half the hardware threads, 1 to 8
  int sceneParserCount() const;
  std::string testSceneWorkerCrashMarker;  // FOR TESTS ONLY
  Limits limits;
  JobLimits jobs;
  std::vector<std::string> corsOrigins;  // empty: no CORS; "*": any origin
  lgh::cli::ContextFlags context;
  // --gpus: the EGL device of each render worker (a device may repeat); empty: one worker on
  // --gpu. allGpus: one worker per EGL device (resolved at start, gpuList()).
  std::vector<int> gpus;
  bool allGpus = false;
  // FOR TESTS ONLY (--test-context-loss GPU:FRAMES): that worker's first renderer reports a lost
  // context after FRAMES frames.
  int testContextLossGpu = -1;
  int testContextLossAfter = -1;

  lgh::RendererOptions rendererOptions() const;
  lgh::RequestLimits requestLimits() const;
  // Each render worker's EGL device. `all` asks EGL how many devices there are; where it cannot
  // say (no device enumeration) that is logged and one worker runs on --gpu.
  std::vector<int> gpuList() const;
};

// "all", or a comma-separated list of EGL device indices ("0,2,3"; "0,0": two workers on one
// device). Throws std::invalid_argument with a message for people.
struct GpuSelection {
  bool all = false;
  std::vector<int> devices;
};
GpuSelection parseGpuSelection(const std::string& text);

// argv[1] of lghd started as the scene parser worker (argv[2]: the test crash marker, if any).
inline constexpr const char* kSceneWorkerFlag = "--scene-parser-worker";

// Parses flags and environment. Returns the configuration, or the process exit code when the
// command line asked for --help/--version or was wrong (the message is printed already).
struct ParsedConfig {
  std::optional<DaemonConfig> config;
  int exitCode = 0;
};
ParsedConfig parseConfig(int argc, char** argv);

}  // namespace lghd
