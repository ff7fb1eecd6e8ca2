// `lgh-bench png`: PNG encoders on the demo's display codes (renderer/bench/.../png_benchmark.hpp).
// Prints a table; with --json the JSON document goes to stdout and the table to stderr.
#include <memory>
#include <string>

#include <fmt/format.h>

#include "bench/bench_command.hpp"
#include "lgh/bench/png_benchmark.hpp"
#include "lgh/task_pool.hpp"

namespace lgh::bench {
namespace {

struct PngFlags {
  std::vector<std::string> sizes = {"1280x720", "256x256"};
  std::vector<int> levels = {1, 6, 9};
  std::vector<int> threads;  // empty: 1 and every hardware thread
  std::vector<std::string> encoders;
  int repeat = 5;
  bool json = false;
};

std::string formatTable(const PngBenchmarkResult& result) {
  std::string out = fmt::format(
      "PNG encoders on the demo's display codes ({}), median of the "
      "timed encodes [ms]\n",
      result.device.glRenderer);
  out += fmt::format("{:<10} {:<16} {:>5} {:>7} {:>10} {:>10} {:>11} {}\n", "image", "encoder",
                     "level", "threads", "median", "min", "bytes", "pixels");
  for (const PngEncoderRun& run : result.runs) {
    out += fmt::format("{:<10} {:<16} {:>5} {:>7} {:>10.2f} {:>10.2f} {:>11} {}\n", run.image,
                       run.encoder, run.level, run.threads, run.medianMs, run.minMs, run.bytes,
                       run.pixelsMatch ? "same" : "DIFFERENT");
  }
  return out;
}

std::pair<int, int> parseSize(const std::string& text) {
  const auto x = text.find('x');
  if (x == std::string::npos) throw CLI::ValidationError("--sizes", "WxH, got " + text);
  return {std::stoi(text.substr(0, x)), std::stoi(text.substr(x + 1))};
}

}  // namespace

Command addPngCommand(CLI::App& app, const cli::ContextFlags& context) {
  auto flags = std::make_shared<PngFlags>();
  CLI::App* sub =
      app.add_subcommand("png", "time PNG encoders (libpng, spng, zlib, libdeflate, strips)");
  sub->add_option("--sizes", flags->sizes, "demo frame sizes, WxH")->delimiter(',');
  sub->add_option("--levels", flags->levels, "zlib levels 0..9")
      ->delimiter(',')
      ->check(CLI::Range(0, 9));
  sub->add_option("--threads", flags->threads,
                  "threads for libdeflate, strips and auto (default: 1 and all)")
      ->delimiter(',')
      ->check(CLI::Range(1, 1024));
  sub->add_option("--encoders", flags->encoders, "only these candidates")->delimiter(',');
  sub->add_option("--repeat", flags->repeat, "timed encodes per run")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_flag("--json", flags->json, "JSON on stdout (the table goes to stderr)");
  return {sub, [flags, &context] {
            PngBenchmarkOptions options;
            options.renderer = cli::rendererOptions(context);
            options.sizes.clear();
            for (const std::string& size : flags->sizes) options.sizes.push_back(parseSize(size));
            options.levels = flags->levels;
            options.threads = flags->threads;
            if (options.threads.empty()) {
              options.threads = {1};
              if (TaskPool::hardwareThreads() > 1) {
                options.threads.push_back(TaskPool::hardwareThreads());
              }
            }
            options.encoders = flags->encoders;
            options.repeat = flags->repeat;
            const PngBenchmarkResult result = runPngBenchmark(options);
            return printResult(result, formatTable(result), flags->json);
          }};
}

}  // namespace lgh::bench
