// lgh-bench subcommands. Each lives in server/bench/<name>.cpp with a function that registers it
// on the app (its flags parsed into state it owns) and returns what to run when it is chosen.
#pragma once

#include <functional>
#include <iostream>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench/result_json.hpp"
#include "cli_common.hpp"

namespace lgh::bench {

struct Command {
  CLI::App* app = nullptr;   // the subcommand, to ask whether it was parsed
  std::function<int()> run;  // exit status; may throw lgh::Error
};

// Prints a report: on stdout, or with --json the JSON document that `document()` makes on stdout
// and the report on stderr (so that `> out.json` keeps both). Returns the exit status.
template <typename MakeDocument>
int printReport(const std::string& report, bool json, const MakeDocument& document) {
  if (json) {
    std::cerr << report;
    std::cout << document().dump(2) << '\n';
  } else {
    std::cout << report;
  }
  return 0;
}

// The same for a benchmark's typed result and its table; the document is the result's JSON
// (bench/result_json.hpp).
template <typename Result>
int printResult(const Result& result, const std::string& table, bool json) {
  return printReport(table, json, [&] { return nlohmann::json(result); });
}

// A VPL count as the tables label it: 1000 -> "1K", 2000000 -> "2M", 1500 -> "1500".
inline std::string countLabel(int count) {
  if (count >= 1000000 && count % 1000000 == 0) return fmt::format("{}M", count / 1000000);
  if (count >= 1000 && count % 1000 == 0) return fmt::format("{}K", count / 1000);
  return std::to_string(count);
}

// `lgh-bench construct`: LGH construction timings (server/bench/construct.cpp).
Command addConstructCommand(CLI::App& app, const cli::ContextFlags& context);
// `lgh-bench render`: full LGH frames (server/bench/render.cpp).
Command addRenderCommand(CLI::App& app, const cli::ContextFlags& context);
// `lgh-bench shadows`: shadowed frames and acceleration-structure builds
// (server/bench/shadows.cpp).
Command addShadowsCommand(CLI::App& app, const cli::ContextFlags& context);
// `lgh-bench handoff`: the GL -> Vulkan hand-off in and out of process (server/bench/handoff.cpp).
Command addHandoffCommand(CLI::App& app, const cli::ContextFlags& context);
// `lgh-bench gi`: whole GI frames, Tables 2 and 3, Fig. 5, quality (server/bench/gi.cpp).
Command addGiCommand(CLI::App& app, const cli::ContextFlags& context);
// `lgh-bench png`: PNG encoders on the demo's display codes (server/bench/png.cpp).
Command addPngCommand(CLI::App& app, const cli::ContextFlags& context);
// `lgh-bench scene-load`: scene parsing in this process and in the worker process
// (server/bench/scene_load.cpp).
Command addSceneLoadCommand(CLI::App& app, const cli::ContextFlags& context);

// argv[1] of lgh-bench started as scene-load's scene parser worker.
inline constexpr const char* kSceneWorkerFlag = "--scene-parser-worker";

}  // namespace lgh::bench
