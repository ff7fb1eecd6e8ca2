// Pieces the command-line tools share: logging set-up and renderer options from flags.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "lgh/renderer.hpp"

namespace lgh::cli {

struct ContextFlags {
  std::string backend = "auto";
  int gpu = 0;
  bool requireGpu = false;
  bool glDebug = false;
  std::string assetRoot = ".";
  std::string logLevel = "warn";
};

// Adds --backend, --gpu, --require-gpu, --gl-debug, --asset-root, --log-level.
void addContextFlags(CLI::App& app, ContextFlags& flags);
RendererOptions rendererOptions(const ContextFlags& flags);
// Logs to stderr at the given level ("trace".."off").
void setUpLogging(const std::string& level);

}  // namespace lgh::cli
