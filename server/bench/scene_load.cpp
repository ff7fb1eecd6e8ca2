// `lgh-bench scene-load FILE...`: scene loading in this process versus in the scene parser worker
// (lgh-bench itself, started with --scene-parser-worker), medians of --repeat cold loads per
// asset, plus the worker's start-up time and idle memory. No GPU needed: nothing is uploaded.
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bench/bench_command.hpp"
#include "lgh/bench/scene_load_benchmark.hpp"

namespace lgh::bench {
namespace {

struct SceneLoadFlags {
  std::vector<std::string> assets;
  int repeat = 10;
};

std::string formatTable(const SceneLoadBenchmarkResult& result) {
  std::string table = fmt::format(
      "scene parser worker: start {:.1f} ms (median), {:.1f} MB of its own when idle\n"
      "{:<28} {:>10} {:>10} {:>12} {:>11} {:>10}\n",
      result.workerStartMs, result.workerIdlePrivateMb, "asset", "triangles", "scene MB",
      "in-process", "in worker", "overhead");
  for (const SceneLoadRow& row : result.rows) {
    table += fmt::format("{:<28} {:>10} {:>10.1f} {:>9.2f} ms {:>8.2f} ms {:>7.2f} ms\n", row.asset,
                         row.triangles, static_cast<double>(row.sceneBytes) / (1 << 20),
                         row.inProcessMs, row.workerMs, row.workerMs - row.inProcessMs);
  }
  return table;
}

}  // namespace

Command addSceneLoadCommand(CLI::App& app, const cli::ContextFlags& /*context*/) {
  auto flags = std::make_shared<SceneLoadFlags>();
  CLI::App* command = app.add_subcommand(
      "scene-load", "scene loading in this process versus in the scene parser worker process");
  command->add_option("assets", flags->assets, ".gltf or .glb files")->required();
  command->add_option("--repeat", flags->repeat, "cold loads per asset (medians)")
      ->check(CLI::Range(1, 1000));
  return {command, [flags] {
            SceneLoadBenchmarkConfig config;
            for (const std::string& asset : flags->assets) {
              config.assets.push_back(std::filesystem::absolute(asset));
            }
            config.repeat = flags->repeat;
            config.workerExecutable = std::filesystem::read_symlink("/proc/self/exe");
            config.workerArguments = {std::string(kSceneWorkerFlag)};
            std::cout << formatTable(runSceneLoadBenchmark(config));
            return 0;
          }};
}

}  // namespace lgh::bench
