// lgh-bench: benchmarks of the lghd renderer on this machine's GPU, one subcommand each.
//   lgh-bench construct --vpls 1000,10000,100000,1000000 [--method gather|scatter|both]
//                       [--levels L|auto] [--iterations K] [--warmup W] [--json] [--gpu N]
//   lgh-bench render ...  (see server/bench/render.cpp)
//   lgh-bench scene-load FILE... [--repeat N]  (see server/bench/scene_load.cpp)
//   lgh-bench shadows ... (see server/bench/shadows.cpp)
//   lgh-bench handoff ... (see server/bench/handoff.cpp)
//   lgh-bench gi ...      (see server/bench/gi.cpp)
//   lgh-bench png ...     (see server/bench/png.cpp)
// Subcommands register themselves from server/bench/<name>.cpp (see bench/bench_command.hpp).
#include <iostream>
#include <string_view>
#include <vector>

#include "allocator_tuning.hpp"
#include "bench/bench_command.hpp"
#include "cli_common.hpp"
#include "crash_report.hpp"
#include "lgh/error.hpp"
#include "lgh/scene_worker.hpp"

// A function-try-block: set-up errors (CLI, logging) end in a message, never in terminate().
int main(int argc, char** argv) try {
  lgh::installCrashReport("lgh-bench");
  if (argc == 2 && std::string_view(argv[1]) == lgh::bench::kSceneWorkerFlag) {
    lgh::keepFreedMemoryForReuse();
    return lgh::runSceneParserWorker(lgh::kSceneWorkerFd);
  }
  CLI::App app{"lgh-bench: benchmarks of the lghd renderer (GPU timer queries, medians)"};
  lgh::cli::ContextFlags context;
  lgh::cli::addContextFlags(app, context);
  app.require_subcommand(1);
  std::vector<lgh::bench::Command> commands{
      lgh::bench::addConstructCommand(app, context), lgh::bench::addRenderCommand(app, context),
      lgh::bench::addSceneLoadCommand(app, context), lgh::bench::addShadowsCommand(app, context),
      lgh::bench::addHandoffCommand(app, context),   lgh::bench::addGiCommand(app, context),
      lgh::bench::addPngCommand(app, context)};
  CLI11_PARSE(app, argc, argv);
  lgh::cli::setUpLogging(context.logLevel);
  for (const auto& command : commands) {
    if (!command.app->parsed()) continue;
    try {
      return command.run();
    } catch (const lgh::Error& error) {
      std::cerr << "lgh-bench: error (" << lgh::errorCodeName(error.code()) << "): " << error.what()
                << '\n';
      return 1;
    } catch (const std::exception& error) {
      std::cerr << "lgh-bench: error: " << error.what() << '\n';
      return 1;
    }
  }
  return 2;
} catch (const std::exception& error) {
  std::cerr << "lgh-bench: error: " << error.what() << '\n';
  return 1;
} catch (...) {
  std::cerr << "lgh-bench: unknown error\n";
  return 1;
}
