// `lgh-bench handoff`: the fixed cost of handing a batch of shadow rays from GL to the Vulkan
// tracer and back in this process, beside what a tracer process would add (a socket round trip
// per frame; file descriptors passed when buffers are reallocated). Prints a table; with --json
// the JSON document goes to stdout and the table to stderr.
#include <memory>
#include <string>

#include <fmt/format.h>

#include "bench/bench_command.hpp"
#include "lgh/bench/handoff_benchmark.hpp"

namespace lgh::bench {
namespace {

struct HandoffFlags {
  int iterations = 1000;
  int warmup = 50;
  bool json = false;
};

std::string row(const char* what, const TimingStats& stats) {
  return fmt::format("{:<44} {:>9.4f} {:>9.4f} {:>9.4f}\n", what, stats.medianMs, stats.minMs,
                     stats.maxMs);
}

std::string formatTable(const HandoffBenchmarkResult& result) {
  std::string out = fmt::format("Shadow-ray hand-off on {} / Vulkan {} ({}), {} iterations [ms]\n",
                                result.device.glRenderer, result.shadows.deviceName,
                                result.transport, result.options.iterations);
  out += fmt::format("{:<44} {:>9} {:>9} {:>9}\n", "", "median", "min", "max");
  out += row("in process: a 1-ray batch GL -> Vulkan -> GL", result.inProcessBatch);
  out += row("a tracer process adds: socket round trip", result.socketRoundTrip);
  out += row("  and on reallocation: 3 fds over SCM_RIGHTS", result.fdPassing);
  return out;
}

}  // namespace

Command addHandoffCommand(CLI::App& app, const cli::ContextFlags& context) {
  auto flags = std::make_shared<HandoffFlags>();
  CLI::App* sub = app.add_subcommand(
      "handoff", "time the GL -> Vulkan shadow-ray hand-off, in process and what a process adds");
  sub->add_option("--iterations", flags->iterations, "timed hand-offs")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--warmup", flags->warmup, "untimed hand-offs first")->capture_default_str();
  sub->add_flag("--json", flags->json, "JSON on stdout (the table goes to stderr)");
  return {sub, [flags, &context] {
            HandoffBenchmarkOptions options;
            options.iterations = flags->iterations;
            options.warmupIterations = flags->warmup;
            options.renderer = cli::rendererOptions(context);
            const HandoffBenchmarkResult result = runHandoffBenchmark(options);
            return printResult(result, formatTable(result), flags->json);
          }};
}

}  // namespace lgh::bench
