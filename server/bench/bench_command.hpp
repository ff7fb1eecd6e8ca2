// lgh-bench subcommands. Each lives in server/bench/<name>.cpp with a function that registers it
// on the app (its flags parsed into state it owns) and returns what to run when it is chosen.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

#include "cli_common.hpp"

namespace lgh::bench {

struct Command {
  CLI::App* app = nullptr;   // the subcommand, to ask whether it was parsed
  std::function<int()> run;  // exit status; may throw lgh::Error
};

// `lgh-bench construct`: LGH construction timings (server/bench/construct.cpp).
Command addConstructCommand(CLI::App& app, const cli::ContextFlags& context);
// `lgh-bench render`: full LGH frames (server/bench/render.cpp).
Command addRenderCommand(CLI::App& app, const cli::ContextFlags& context);

}  // namespace lgh::bench
