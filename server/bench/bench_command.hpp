// lgh-bench subcommands. Each lives in server/bench/<name>.cpp with a function that registers it
// on the app (its flags parsed into state it owns) and returns what to run when it is chosen.
#pragma once

#include <functional>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"

namespace lgh::bench {

struct Command {
  CLI::App* app = nullptr;   // the subcommand, to ask whether it was parsed
  std::function<int()> run;  // exit status; may throw lgh::Error
};

// Prints a benchmark's result: the table on stdout, or with --json the JSON document on stdout
// and the table on stderr (so that `> out.json` keeps both). Returns the exit status.
inline int printResult(const nlohmann::json& result, const std::string& table, bool json) {
  if (json) {
    std::cerr << table;
    std::cout << result.dump(2) << '\n';
  } else {
    std::cout << table;
  }
  return 0;
}

// `lgh-bench construct`: LGH construction timings (server/bench/construct.cpp).
Command addConstructCommand(CLI::App& app, const cli::ContextFlags& context);
// `lgh-bench render`: full LGH frames (server/bench/render.cpp).
Command addRenderCommand(CLI::App& app, const cli::ContextFlags& context);

}  // namespace lgh::bench
