// Pieces the command-line tools share: logging set-up and renderer options from flags.
#pragma once

#include <algorithm>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "lgh/renderer.hpp"

namespace lgh::cli {

struct ContextFlags {
  std::string backend = "auto";
  int gpu = 0;
  bool requireGpu = false;
  bool glDebug = false;
  bool noFrameOverlap = false;
  bool glWorker = false;
  int uploadStagingMb = -1;
  std::string assetRoot = ".";
  std::string logLevel = "warn";
};

// Adds --backend, --gpu, --require-gpu, --gl-debug, --no-frame-overlap, --gl-worker,
// --upload-staging-mb, --asset-root, --log-level.
void addContextFlags(CLI::App& app, ContextFlags& flags);
RendererOptions rendererOptions(const ContextFlags& flags);
// Logs to stderr at the given level ("trace".."off").
void setUpLogging(const std::string& level);

// The names of an enum's EnumNames table (lgh/enum_names.hpp), for CLI::IsMember, leaving out
// `skip`: one table for the request parser, the daemon and the command lines.
template <typename Enum>
std::vector<std::string> enumChoices(std::initializer_list<std::string_view> skip = {}) {
  std::vector<std::string> names;
  for (const auto& entry : EnumNames<Enum>::names) {
    if (std::find(skip.begin(), skip.end(), entry.name) == skip.end()) {
      names.emplace_back(entry.name);
    }
  }
  return names;
}

// A name checked by CLI::IsMember(enumChoices<Enum>()) back to its value.
template <typename Enum>
Enum enumValue(const std::string& name) {
  return *enumFromName<Enum>(name);
}

}  // namespace lgh::cli
