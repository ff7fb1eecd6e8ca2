#include "config.hpp"

#include <algorithm>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include <spdlog/spdlog.h>

#include "lgh/egl_devices.hpp"
#include "lgh/task_pool.hpp"
#include "version.hpp"

namespace lghd {
namespace {

constexpr const char* kDescription =
    "lghd: headless GPU render service. POST a render request (JSON, see /openapi.json) to\n"
    "/v1/render and get a PNG or EXR back; POST /v1/thumbnails renders a batch of glTF assets;\n"
    "POST /v1/jobs takes long work (a render, a batch, a benchmark) and answers 202 at once.\n"
    "With no flags it serves the built-in demo scene on 127.0.0.1:8080:\n"
    "  lghd &\n"
    "  curl -s -X POST localhost:8080/v1/render -d '{}' -o demo.png\n"
    "Every flag has an environment variable (shown as Env); a flag on the command line wins.";

constexpr const char* kFooter =
    "Exit status: 0 after a clean shutdown (SIGTERM/SIGINT), 1 when the GL context or the\n"
    "self-test render fails, 2 for a bad command line, 3 when the watchdog found the render\n"
    "thread hung. Documentation: docs/DAEMON.md.";

// Numbers as the command line sees them; converted to DaemonConfig's units afterwards.
struct RawFlags {
  double deadlineSeconds = 30.0;
  double graceSeconds = 10.0;
  double watchdogSeconds = 60.0;
  std::size_t sceneCacheMb = 512;
  std::size_t maxBodyMb = 64;
  int testRenderDelayMs = 0;
  std::size_t readbackMb = 512;
  std::string authTokenFile;
  std::string sceneWorker = "on";
  std::size_t jobsMemoryMb = 1024;
  double jobTtlSeconds = 600.0;
  double jobDeadlineSeconds = 600.0;
  std::string corsOrigins;
  std::string gpus;
  std::string testContextLoss;
};

void addServerFlags(CLI::App& app, DaemonConfig& config, RawFlags& raw) {
  const char* group = "Server";
  app.add_option("--host", config.host, "address to listen on (0.0.0.0: every interface)")
      ->envname("LGHD_HOST")
      ->capture_default_str()
      ->group(group);
  app.add_option("--port", config.port, "TCP port; 0 picks a free one (printed on stdout)")
      ->envname("LGHD_PORT")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str()
      ->group(group);
  app.add_option("--metrics-port", config.metricsPort,
                 "also serve GET /metrics, /healthz and /readyz on this port, without the bearer "
                 "token (for scrapers that send none); 0 picks a free one (printed on stdout); "
                 "-1: none")
      ->envname("LGHD_METRICS_PORT")
      ->check(CLI::Range(-1, 65535))
      ->capture_default_str()
      ->group(group);
  app.add_option("--http-threads", config.httpThreads,
                 "HTTP worker threads (each serves one connection at a time)")
      ->envname("LGHD_HTTP_THREADS")
      ->check(CLI::Range(2, 1024))
      ->capture_default_str()
      ->group(group);
  app.add_option("--auth-token", config.authToken,
                 "require 'Authorization: Bearer TOKEN' on every route but /healthz and /readyz "
                 "(prefer the variable or --auth-token-file: flags show in ps)")
      ->envname("LGHD_AUTH_TOKEN")
      ->group(group);
  app.add_option("--auth-token-file", raw.authTokenFile, "read the bearer token from this file")
      ->envname("LGHD_AUTH_TOKEN_FILE")
      ->check(CLI::ExistingFile)
      ->group(group);
  app.add_option("--grace-seconds", raw.graceSeconds,
                 "on SIGTERM/SIGINT, how long queued renders may still finish before the rest "
                 "are answered 503")
      ->envname("LGHD_GRACE_SECONDS")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str()
      ->group(group);
  app.add_option("--cors-origin", raw.corsOrigins,
                 "answer browsers from these origins (comma-separated, or *) with CORS headers; "
                 "preflight requests are answered before authentication")
      ->envname("LGHD_CORS_ORIGIN")
      ->group(group);
  app.add_option("--log-format", config.logFormat, "json (one object per line) or text")
      ->envname("LGHD_LOG_FORMAT")
      ->check(CLI::IsMember({"json", "text"}))
      ->capture_default_str()
      ->group(group);
}

void addRenderFlags(CLI::App& app, DaemonConfig& config, RawFlags& raw) {
  const char* group = "Rendering";
  app.add_option("--queue-depth", config.queueDepth,
                 "renders that may wait for the render thread; beyond that: 429 + Retry-After")
      ->envname("LGHD_QUEUE_DEPTH")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str()
      ->group(group);
  app.add_option("--deadline-seconds", raw.deadlineSeconds,
                 "per-request deadline (queue wait + render); past it: 504. A request's "
                 "X-Lgh-Deadline-Ms header may shorten it")
      ->envname("LGHD_DEADLINE_SECONDS")
      ->check(CLI::Range(0.001, 86400.0))
      ->capture_default_str()
      ->group(group);
  app.add_option("--scene-cache-mb", raw.sceneCacheMb,
                 "GPU memory budget of the scene cache (LRU by content hash), MiB")
      ->envname("LGHD_SCENE_CACHE_MB")
      ->capture_default_str()
      ->group(group);
  app.add_option("--watchdog-seconds", raw.watchdogSeconds,
                 "a render still running this long past its deadline (or a renderer start-up "
                 "this long past 30 s) counts as a hung GPU: lghd answers 503, turns not ready and "
                 "exits 3 for its supervisor to restart it; 0: no watchdog")
      ->envname("LGHD_WATCHDOG_SECONDS")
      ->check(CLI::Range(0.0, 86400.0))
      ->capture_default_str()
      ->group(group);
  app.add_option("--encode-threads", config.output.encodeThreads,
                 "threads that encode finished frames (PNG/EXR) while the GPU renders the next "
                 "ones; 0: one per hardware thread")
      ->envname("LGHD_ENCODE_THREADS")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str()
      ->group(group);
  app.add_option("--frames-in-flight", config.output.framesInFlight,
                 "frames between submission to the GPU and the end of their encoding; the render "
                 "thread waits beyond it. 0: twice the encode threads")
      ->envname("LGHD_FRAMES_IN_FLIGHT")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str()
      ->group(group);
  app.add_option("--readback-mb", raw.readbackMb,
                 "memory for the pixels of frames in flight, MiB (a frame larger than this alone "
                 "still renders, by itself)")
      ->envname("LGHD_READBACK_MB")
      ->check(CLI::PositiveNumber)
      ->capture_default_str()
      ->group(group);
  app.add_option("--gpus", raw.gpus,
                 "one render worker per listed EGL device, scheduled by load: 'all', or indices "
                 "such as 0,2,3 (an index may repeat: two workers on one device). Default: one "
                 "worker on --gpu")
      ->envname("LGHD_GPUS")
      ->group("GPU and context");
  app.add_option("--scene-worker", raw.sceneWorker,
                 "parse scene assets in a worker process (on), so that a parser crash fails one "
                 "request, not lghd; or in lghd's own process (off)")
      ->envname("LGHD_SCENE_WORKER")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str()
      ->group(group);
  app.add_option("--scene-parsers", config.sceneParsers,
                 "scene parser worker processes per render worker: the scenes it draws next "
                 "parse side by side (each process has --scene-worker-memory-mb); 0: half the "
                 "hardware threads, at least 1 and at most 8")
      ->envname("LGHD_SCENE_PARSERS")
      ->check(CLI::Range(0, 64))
      ->capture_default_str()
      ->group(group);
  app.add_option("--test-scene-worker-crash-marker", config.testSceneWorkerCrashMarker,
                 "FOR TESTS ONLY: the scene parser worker crashes (SIGSEGV) on assets whose name "
                 "contains this text")
      ->envname("LGHD_TEST_SCENE_WORKER_CRASH_MARKER")
      ->group("Testing");
  app.add_option("--test-context-loss", raw.testContextLoss,
                 "FOR TESTS ONLY: GPU:FRAMES, the first renderer of render worker GPU (its place "
                 "in --gpus) reports a lost context after FRAMES frames")
      ->envname("LGHD_TEST_CONTEXT_LOSS")
      ->group("Testing");
  app.add_option("--test-render-delay-ms", raw.testRenderDelayMs,
                 "FOR TESTS ONLY: sleep this long on the render thread before each render")
      ->envname("LGHD_TEST_RENDER_DELAY_MS")
      ->check(CLI::Range(0, 600000))
      ->group("Testing");
}

void addLimitFlags(CLI::App& app, Limits& limits, RawFlags& raw) {
  const char* group = "Limits (413 when exceeded)";
  auto add = [&](const char* name, auto& value, const char* help, const char* env) {
    app.add_option(name, value, help)
        ->envname(env)
        ->check(CLI::PositiveNumber)
        ->capture_default_str()
        ->group(group);
  };
  add("--max-body-mb", raw.maxBodyMb, "request body size, MiB (uploads included)",
      "LGHD_MAX_BODY_MB");
  add("--max-width", limits.maxWidth, "image width, pixels", "LGHD_MAX_WIDTH");
  add("--max-height", limits.maxHeight, "image height, pixels", "LGHD_MAX_HEIGHT");
  add("--max-pixels", limits.maxPixels, "width * height", "LGHD_MAX_PIXELS");
  add("--max-lights", limits.maxLights, "lights given in a request", "LGHD_MAX_LIGHTS");
  add("--max-vpls", limits.maxVpls, "VPLs (settings.lgh.vpl_count)", "LGHD_MAX_VPLS");
  add("--max-triangles", limits.maxTriangles, "triangles drawn for one scene",
      "LGHD_MAX_TRIANGLES");
  add("--max-texture-size", limits.maxTextureSize, "texture width or height, pixels",
      "LGHD_MAX_TEXTURE_SIZE");
  add("--max-texture-mb", limits.maxTextureMb,
      "all texture images of one scene, decoded to RGBA8, MiB", "LGHD_MAX_TEXTURE_MB");
  add("--max-batch", limits.maxBatch, "thumbnails in one batch (assets x views)", "LGHD_MAX_BATCH");
}

void addSceneWorkerLimitFlags(CLI::App& app, DaemonConfig& config) {
  const char* group = "Limits (413 when exceeded)";
  app.add_option("--scene-worker-memory-mb", config.sceneWorkerMemoryMb,
                 "memory of the scene parser worker (its data size), MiB")
      ->envname("LGHD_SCENE_WORKER_MEMORY_MB")
      ->check(CLI::Range(std::size_t{256}, std::size_t{1} << 30))
      ->capture_default_str()
      ->group(group);
  app.add_option("--scene-worker-timeout-seconds", config.sceneWorkerTimeoutSeconds,
                 "time to parse one asset in the scene parser worker")
      ->envname("LGHD_SCENE_WORKER_TIMEOUT_SECONDS")
      ->check(CLI::Range(0.1, 86400.0))
      ->capture_default_str()
      ->group(group);
}

void addJobFlags(CLI::App& app, JobLimits& jobs, RawFlags& raw) {
  const char* group = "Jobs (POST /v1/jobs)";
  app.add_option("--max-jobs", jobs.maxJobs,
                 "jobs held at once (queued, running, finished within the TTL); beyond: 429")
      ->envname("LGHD_MAX_JOBS")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str()
      ->group(group);
  app.add_option("--jobs-memory-mb", raw.jobsMemoryMb,
                 "memory for job results, MiB (a job reserves its result's upper bound)")
      ->envname("LGHD_JOBS_MEMORY_MB")
      ->check(CLI::PositiveNumber)
      ->capture_default_str()
      ->group(group);
  app.add_option("--job-ttl-seconds", raw.jobTtlSeconds,
                 "how long a finished job's status and result are kept")
      ->envname("LGHD_JOB_TTL_SECONDS")
      ->check(CLI::Range(1.0, 7.0 * 86400.0))
      ->capture_default_str()
      ->group(group);
  app.add_option("--max-job-batch", jobs.maxBatch,
                 "thumbnails (assets x views) or benchmark renders in one job")
      ->envname("LGHD_MAX_JOB_BATCH")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str()
      ->group(group);
  app.add_option("--job-deadline-seconds", raw.jobDeadlineSeconds,
                 "deadline of each render of a job (queue wait + render)")
      ->envname("LGHD_JOB_DEADLINE_SECONDS")
      ->check(CLI::Range(0.001, 86400.0))
      ->capture_default_str()
      ->group(group);
}

std::vector<std::string> splitOrigins(const std::string& list) {
  std::vector<std::string> origins;
  std::stringstream stream(list);
  for (std::string origin; std::getline(stream, origin, ',');) {
    const auto begin = origin.find_first_not_of(" \t");
    if (begin == std::string::npos) continue;
    const auto end = origin.find_last_not_of(" \t");
    origins.push_back(origin.substr(begin, end - begin + 1));
  }
  return origins;
}

void addContextEnvNames(CLI::App& app) {
  app.get_option("--backend")->envname("LGHD_BACKEND")->group("GPU and context");
  app.get_option("--gpu")->envname("LGHD_GPU")->group("GPU and context");
  app.get_option("--require-gpu")->envname("LGHD_REQUIRE_GPU")->group("GPU and context");
  app.get_option("--gl-debug")->envname("LGHD_GL_DEBUG")->group("GPU and context");
  app.get_option("--no-frame-overlap")->envname("LGHD_NO_FRAME_OVERLAP")->group("GPU and context");
  app.get_option("--gl-worker")->envname("LGHD_GL_WORKER")->group("GPU and context");
  app.get_option("--upload-staging-mb")
      ->envname("LGHD_UPLOAD_STAGING_MB")
      ->group("GPU and context");
  app.get_option("--asset-root")->envname("LGHD_ASSET_ROOT")->group("GPU and context");
  app.get_option("--log-level")->envname("LGHD_LOG_LEVEL")->group("Server");
}

std::string readTokenFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string token = text.str();
  const auto end = token.find_last_not_of(" \t\r\n");
  return end == std::string::npos ? std::string() : token.substr(0, end + 1);
}

template <class Duration>
Duration fromSeconds(double seconds) {
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(seconds));
}

void applyRawFlags(const RawFlags& raw, DaemonConfig& config) {
  config.deadline = fromSeconds<std::chrono::milliseconds>(raw.deadlineSeconds);
  config.grace = fromSeconds<std::chrono::milliseconds>(raw.graceSeconds);
  config.watchdog = fromSeconds<std::chrono::milliseconds>(raw.watchdogSeconds);
  config.sceneCacheBytes = raw.sceneCacheMb << 20;
  config.limits.maxBodyBytes = raw.maxBodyMb << 20;
  config.testRenderDelay = std::chrono::milliseconds(raw.testRenderDelayMs);
  config.output.readbackBytes = raw.readbackMb << 20;
  config.sceneWorker = raw.sceneWorker == "on";
  if (!raw.authTokenFile.empty()) config.authToken = readTokenFile(raw.authTokenFile);
  config.jobs.memoryBytes = raw.jobsMemoryMb << 20;
  config.jobs.ttl = fromSeconds<std::chrono::seconds>(raw.jobTtlSeconds);
  config.jobs.renderDeadline = fromSeconds<std::chrono::milliseconds>(raw.jobDeadlineSeconds);
  config.corsOrigins = splitOrigins(raw.corsOrigins);
}

// "GPU:FRAMES" of --test-context-loss.
std::pair<int, int> parseContextLoss(const std::string& text) {
  const auto colon = text.find(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument(text);
    return {std::stoi(text.substr(0, colon)), std::stoi(text.substr(colon + 1))};
  } catch (const std::logic_error&) {
    throw std::invalid_argument("--test-context-loss: expected GPU:FRAMES, got '" + text + "'");
  }
}

}  // namespace

GpuSelection parseGpuSelection(const std::string& text) {
  GpuSelection selection;
  if (text == "all") {
    selection.all = true;
    return selection;
  }
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    const auto begin = item.find_first_not_of(" \t");
    const auto end = item.find_last_not_of(" \t");
    const std::string index =
        begin == std::string::npos ? std::string() : item.substr(begin, end - begin + 1);
    if (index.empty() || index.size() > 4 ||
        index.find_first_not_of("0123456789") != std::string::npos) {
      throw std::invalid_argument("--gpus: '" + index +
                                  "' is not an EGL device index (give 'all' or indices such as "
                                  "0,2,3)");
    }
    selection.devices.push_back(std::stoi(index));
  }
  if (selection.devices.empty()) {
    throw std::invalid_argument("--gpus: give 'all' or EGL device indices such as 0,2,3");
  }
  if (selection.devices.size() > 64) {
    throw std::invalid_argument("--gpus: at most 64 render workers");
  }
  return selection;
}

std::vector<int> DaemonConfig::gpuList() const {
  if (!allGpus) return gpus.empty() ? std::vector<int>{context.gpu} : gpus;
  std::vector<int> devices;
  try {
    const int count = lgh::eglDeviceCount();
    for (int i = 0; i < count; ++i) devices.push_back(i);
  } catch (const std::exception& error) {
    spdlog::warn("--gpus all: EGL cannot list its devices ({}); one render worker on --gpu {}",
                 error.what(), context.gpu);
  }
  if (devices.empty()) devices.push_back(context.gpu);
  return devices;
}

int OutputOptions::encoderCount() const {
  return encodeThreads > 0 ? encodeThreads : lgh::TaskPool::hardwareThreads();
}

int DaemonConfig::sceneParserCount() const {
  return sceneParsers > 0 ? sceneParsers : std::clamp(lgh::TaskPool::hardwareThreads() / 2, 1, 8);
}

std::size_t OutputOptions::frameLimit() const {
  return static_cast<std::size_t>(framesInFlight > 0 ? framesInFlight : 2 * encoderCount());
}

lgh::RendererOptions DaemonConfig::rendererOptions() const {
  lgh::RendererOptions options = lgh::cli::rendererOptions(context);
  options.maxTriangles = limits.maxTriangles;
  options.maxTextureSize = limits.maxTextureSize;
  options.maxTextureBytes = limits.maxTextureMb << 20;
  options.sceneCacheBytes = sceneCacheBytes;
  if (sceneWorker) {
    std::error_code error;
    options.sceneWorker.executable = std::filesystem::read_symlink("/proc/self/exe", error);
    options.sceneWorker.arguments = {kSceneWorkerFlag};
    if (!testSceneWorkerCrashMarker.empty()) {
      options.sceneWorker.arguments.push_back(testSceneWorkerCrashMarker);
    }
    options.sceneWorker.memoryBytes = sceneWorkerMemoryMb << 20;
    options.sceneWorker.timeoutSeconds = sceneWorkerTimeoutSeconds;
    options.sceneWorker.processes = static_cast<std::size_t>(sceneParserCount());
  }
  return options;
}

lgh::RequestLimits DaemonConfig::requestLimits() const {
  lgh::RequestLimits requestLimits;
  requestLimits.maxWidth = limits.maxWidth;
  requestLimits.maxHeight = limits.maxHeight;
  requestLimits.maxPixels = limits.maxPixels;
  requestLimits.maxLights = limits.maxLights;
  requestLimits.maxVpls = limits.maxVpls;
  requestLimits.maxInlineGlbBytes = limits.maxBodyBytes;
  return requestLimits;
}

ParsedConfig parseConfig(int argc, char** argv) {
  CLI::App app{kDescription, "lghd"};
  app.footer(kFooter);
  app.set_version_flag("--version", std::string("lghd ") + kVersion);
  app.get_formatter()->column_width(34);

  DaemonConfig config;
  config.context.logLevel = "info";
  RawFlags raw;
  addServerFlags(app, config, raw);
  lgh::cli::addContextFlags(app, config.context);
  addContextEnvNames(app);
  addRenderFlags(app, config, raw);
  addLimitFlags(app, config.limits, raw);
  addSceneWorkerLimitFlags(app, config);
  addJobFlags(app, config.jobs, raw);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);  // prints the help, the version or the message
    return {std::nullopt, code == 0 ? 0 : 2};
  }
  applyRawFlags(raw, config);
  try {
    if (!raw.gpus.empty()) {
      const GpuSelection selection = parseGpuSelection(raw.gpus);
      config.allGpus = selection.all;
      config.gpus = selection.devices;
    }
    if (!raw.testContextLoss.empty()) {
      std::tie(config.testContextLossGpu, config.testContextLossAfter) =
          parseContextLoss(raw.testContextLoss);
    }
  } catch (const std::invalid_argument& error) {
    std::cerr << "lghd: " << error.what() << "\n";
    return {std::nullopt, 2};
  }
  if (!raw.authTokenFile.empty() && config.authToken.empty()) {
    std::cerr << "lghd: the token file " << raw.authTokenFile << " is empty\n";
    return {std::nullopt, 2};
  }
  return {std::move(config), 0};
}

}  // namespace lghd
