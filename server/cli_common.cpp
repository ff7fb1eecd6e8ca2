#include "cli_common.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace lgh::cli {

void addContextFlags(CLI::App& app, ContextFlags& flags) {
  app.add_option("--backend", flags.backend,
                 "GL context path: auto (egl-device, then surfaceless, then osmesa), egl-device, "
                 "surfaceless, osmesa")
      ->check(CLI::IsMember(enumChoices<ContextBackend>()))
      ->envname("LGH_BACKEND")
      ->capture_default_str();
  app.add_option("--gpu", flags.gpu, "EGL device index (EGL's order, not CUDA's)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_flag("--require-gpu", flags.requireGpu,
               "fail instead of rendering on a software rasterizer");
  app.add_flag("--gl-debug", flags.glDebug, "create a KHR_debug context");
  app.add_flag("--no-frame-overlap", flags.noFrameOverlap,
               "issue each shadowed frame whole: GL waits for its shadow rays before it draws the "
               "next frame (by default the next frame's G-buffer runs while Vulkan traces)");
  app.add_flag("--gl-worker", flags.glWorker,
               "upload the scenes parsed ahead and free evicted ones on a second GL context, on a "
               "thread of its own (off: the render thread does both; slower on NVIDIA's driver, "
               "docs/BENCHMARKS.md)");
  app.add_option("--upload-staging-mb", flags.uploadStagingMb,
                 "memory that prefetch threads copy parsed scenes of 1 MiB or more into, so that "
                 "the render thread uploads them as GPU copies; -1: 128 on a GPU, 0 on a software "
                 "rasterizer or with --gl-worker; 0: none")
      ->check(CLI::Range(-1, 65536))
      ->envname("LGH_UPLOAD_STAGING_MB")
      ->capture_default_str();
  app.add_option("--asset-root", flags.assetRoot, "folder that scene asset paths resolve inside")
      ->capture_default_str();
  app.add_option("--log-level", flags.logLevel, "trace, debug, info, warn, error, off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}))
      ->capture_default_str();
}

RendererOptions rendererOptions(const ContextFlags& flags) {
  RendererOptions options;
  options.backend = parseContextBackend(flags.backend);
  options.gpuIndex = flags.gpu;
  options.requireGpu = flags.requireGpu;
  options.glDebug = flags.glDebug;
  options.overlapShadowedFrames = !flags.noFrameOverlap;
  options.glWorker = flags.glWorker;
  options.uploadStagingBytes =
      flags.uploadStagingMb < 0 ? -1 : static_cast<std::int64_t>(flags.uploadStagingMb) << 20;
  options.assetRoot = flags.assetRoot;
  return options;
}

void setUpLogging(const std::string& level) {
  auto logger = spdlog::stderr_color_mt("lgh");
  spdlog::set_default_logger(logger);
  spdlog::set_level(spdlog::level::from_str(level));
}

}  // namespace lgh::cli
