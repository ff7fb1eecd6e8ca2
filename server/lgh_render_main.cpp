// lgh-render: renders one request to a file and prints the timing table.
//   lgh-render REQUEST.json -o OUT.png|OUT.exr [--timings OUT.json] [--gpu N]
//              [--width W --height H]
//   lgh-render --demo -o demo.png
//   lgh-render MODEL.glb|MODEL.gltf -o OUT.png [--size 256|WxH] [--view iso|front|side|top|X,Y,Z]
//              [--transparent]          (a thumbnail: no request JSON; see thumbnail_cli.hpp)
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "crash_report.hpp"
#include "lgh/error.hpp"
#include "lgh/renderer.hpp"
#include "lgh/task_pool.hpp"
#include "thumbnail_cli.hpp"

namespace {

struct Flags {
  std::string requestPath;  // a request JSON, '-' (stdin), or a .glb/.gltf model
  bool demo = false;
  std::string size;  // --size: "" (the request's own; 256 for a model), "N" or "WxH"
  std::string view;  // --view: "" (iso for a model)
  bool transparent = false;
  std::string output;
  std::string timingsPath;
  int width = 0;
  int height = 0;
  int pngCompression = -1;  // -1: the request's own
  bool quiet = false;
  int repeat = 1;
  int encodeThreads = 0;  // 0: one per hardware thread
  lgh::cli::ContextFlags context;
};

std::string readText(const std::string& path) {
  if (path == "-") {
    std::stringstream text;
    text << std::cin.rdbuf();
    return text.str();
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw lgh::Error(lgh::ErrorCode::NotFound, "cannot open request file", path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

constexpr lgh::cli::ImageSize kThumbnailSize{256, 256};

// The request JSON with the command line's overrides applied before validation, so the same
// limits and checks hold for both. A model becomes the request of its thumbnail.
nlohmann::json requestJson(const Flags& flags) {
  nlohmann::json json = nlohmann::json::object();
  if (!flags.demo && lgh::cli::isModelFile(flags.requestPath)) {
    json = lgh::cli::modelRequest(
        flags.requestPath, lgh::cli::parseImageSize(flags.size).value_or(kThumbnailSize),
        *lgh::cli::parseViewDirection(flags.view.empty() ? "iso" : flags.view), flags.transparent);
  } else if (!flags.demo) {
    std::string text = readText(flags.requestPath);
    try {
      json = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& error) {
      throw lgh::Error(lgh::ErrorCode::BadRequest, std::string("malformed JSON: ") + error.what(),
                       flags.requestPath);
    }
    if (!json.is_object()) {
      throw lgh::Error(lgh::ErrorCode::BadRequest, "a request must be a JSON object",
                       flags.requestPath);
    }
  }
  auto& output = json["output"];
  if (output.is_null()) output = nlohmann::json::object();
  if (!output.is_object()) return json;  // let validation name it
  if (const auto size = lgh::cli::parseImageSize(flags.size)) {
    output["width"] = size->width;
    output["height"] = size->height;
  }
  if (flags.transparent) output["transparent_background"] = true;
  if (flags.width > 0) output["width"] = flags.width;
  if (flags.height > 0) output["height"] = flags.height;
  if (flags.pngCompression >= 0) output["png_compression"] = flags.pngCompression;
  const std::string format = output.value("format", std::string("png"));
  if (endsWith(flags.output, ".png")) {
    output["format"] = "png";
  } else if (endsWith(flags.output, ".exr") && format == "png") {
    output["format"] = "exr-half";
  }
  if (output.empty()) json.erase("output");
  return json;
}

lgh::TimingTable medianTimings(const std::vector<lgh::TimingTable>& runs) {
  lgh::TimingTable median;
  for (const auto& row : runs.front().rows) {
    std::vector<double> values;
    values.reserve(runs.size());
    for (const auto& run : runs) values.push_back(run.get(row.name));
    std::sort(values.begin(), values.end());
    median.add(row.name, row.clock, values[values.size() / 2]);
  }
  return median;
}

// Frames rendered as lghd renders them: submitted back to back (the GPU works on one while the
// next is issued), read back asynchronously, encoded on a pool of threads. The render thread waits
// when `limit` frames are between submission and the end of their encoding.
class PipelinedFrames {
 public:
  PipelinedFrames(lgh::Renderer& renderer, int encodeThreads)
      : renderer_(renderer),
        encoders_(encodeThreads, "lgh-encode"),
        limit_(static_cast<std::size_t>(2 * encoders_.threads() +
                                        renderer.options().framesInFlight)) {}

  void submit(const lgh::RenderRequest& request) {
    {
      std::unique_lock lock(mutex_);
      encoded_.wait(lock, [&] { return outstanding_ < limit_; });
      ++outstanding_;
    }
    starts_.push_back(std::chrono::steady_clock::now());
    renderer_.submit(request);
    while (auto result = renderer_.finish(false)) encode(std::move(*result));
  }

  // Every frame submitted since the last drain, encoded (in the order their encodings ended).
  std::vector<lgh::RenderResult> drain() {
    while (auto result = renderer_.finish(true)) encode(std::move(*result));
    encoders_.waitIdle();
    std::lock_guard lock(mutex_);
    if (error_) std::rethrow_exception(error_);
    return std::move(done_);
  }

 private:
  void encode(lgh::RenderResult result) {
    const auto start = starts_.at(finished_++);
    const auto finished = std::chrono::steady_clock::now();
    encoders_.submit([this, start, finished, result = std::move(result)]() mutable {
      const auto encodeStart = std::chrono::steady_clock::now();
      try {
        result.encoded = result.encode(&encoders_);
      } catch (...) {
        std::lock_guard lock(mutex_);
        if (!error_) error_ = std::current_exception();
      }
      result.mimeType = lgh::mimeType(result.output.format);
      result.pixels.release();
      const auto end = std::chrono::steady_clock::now();
      result.timings.add("encode wait", lgh::TimingRow::Clock::Cpu, ms(finished, encodeStart));
      result.timings.add("encode", lgh::TimingRow::Clock::Cpu, ms(encodeStart, end));
      result.timings.add("total", lgh::TimingRow::Clock::Cpu, ms(start, end));
      std::lock_guard lock(mutex_);
      done_.push_back(std::move(result));
      --outstanding_;
      encoded_.notify_all();
    });
  }

  static double ms(std::chrono::steady_clock::time_point from,
                   std::chrono::steady_clock::time_point to) {
    return std::chrono::duration<double, std::milli>(to - from).count();
  }

  lgh::Renderer& renderer_;
  lgh::TaskPool encoders_;
  std::size_t limit_;
  std::vector<std::chrono::steady_clock::time_point> starts_;  // render thread
  std::size_t finished_ = 0;                                   // render thread
  std::mutex mutex_;
  std::condition_variable encoded_;
  std::size_t outstanding_ = 0;
  std::vector<lgh::RenderResult> done_;
  std::exception_ptr error_;
};

int run(const Flags& flags) {
  if (!endsWith(flags.output, ".png") && !endsWith(flags.output, ".exr")) {
    throw lgh::Error(lgh::ErrorCode::BadRequest, "the output file must end in .png or .exr",
                     flags.output);
  }
  lgh::RenderRequest request = lgh::parseRenderRequest(requestJson(flags));
  lgh::cli::ContextFlags context = flags.context;
  if (!flags.demo && lgh::cli::isModelFile(flags.requestPath)) {
    if (!std::filesystem::is_regular_file(flags.requestPath)) {
      throw lgh::Error(lgh::ErrorCode::NotFound, "cannot open the model", flags.requestPath);
    }
    context.assetRoot = lgh::cli::modelAssetRoot(flags.requestPath);
  }
  lgh::Renderer renderer(lgh::cli::rendererOptions(context));
  PipelinedFrames frames(renderer, flags.encodeThreads);
  // The first frame alone (shaders compiled, scene loaded: the cold frame), then the warm ones
  // back to back.
  frames.submit(request);
  std::vector<lgh::RenderResult> results = frames.drain();
  const auto warmStart = std::chrono::steady_clock::now();
  for (int i = 1; i < flags.repeat; ++i) frames.submit(request);
  std::vector<lgh::RenderResult> warm = frames.drain();
  const double warmSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - warmStart).count();
  lgh::RenderResult result = std::move(warm.empty() ? results.front() : warm.back());
  if (!warm.empty()) {
    // Warm frames: the scene is cached and shaders are compiled; report each row's median.
    std::vector<lgh::TimingTable> runs;
    runs.reserve(warm.size());
    for (const auto& frame : warm) runs.push_back(frame.timings);
    result.timings = medianTimings(runs);
  }
  lgh::image_io::writeFile(flags.output, result.encoded);
  if (!flags.timingsPath.empty()) {
    nlohmann::json summary = result.summaryJson();
    if (!warm.empty()) {
      summary["warm_frames_per_second"] = static_cast<double>(warm.size()) / warmSeconds;
    }
    std::ofstream(flags.timingsPath) << summary.dump(2) << '\n';
  }
  if (!flags.quiet) {
    const auto& device = result.device;
    std::cout << fmt::format("{} ({}x{}) on {} | {} | {}\n", flags.output, request.output.width,
                             request.output.height, device.contextPath, device.glRenderer,
                             device.glVersion);
    for (const auto& warning : result.warnings) std::cout << "warning: " << warning << '\n';
    std::cout << result.timings.format();
    if (!warm.empty()) {
      std::cout << fmt::format("{} warm frames in {:.3f} s: {:.1f} frames/s (pipelined)\n",
                               warm.size(), warmSeconds,
                               static_cast<double>(warm.size()) / warmSeconds);
    }
  }
  return 0;
}

}  // namespace

// A function-try-block: set-up errors (CLI, logging) end in a message, never in terminate().
int main(int argc, char** argv) try {
  lgh::installCrashReport("lgh-render");
  CLI::App app{
      "lgh-render: render one lghd request (JSON) to a PNG or EXR file, or a thumbnail of a glTF "
      "model:\n  lgh-render model.glb -o model.png --size 256 --view iso --transparent"};
  Flags flags;
  auto* requestOption = app.add_option(
      "request", flags.requestPath,
      "request JSON file ('-' for stdin), or a .glb/.gltf model to make a thumbnail of (its "
      "folder is the asset root)");
  auto* demoFlag = app.add_flag("--demo", flags.demo, "render the built-in demo scene");
  requestOption->excludes(demoFlag);
  app.add_option("-o,--output", flags.output, "output file: .png (8-bit sRGB) or .exr (linear)")
      ->required();
  app.add_option("--timings", flags.timingsPath, "write the timing table and device as JSON");
  app.add_option("--width", flags.width, "override the request's output width")
      ->check(CLI::PositiveNumber);
  app.add_option("--height", flags.height, "override the request's output height")
      ->check(CLI::PositiveNumber);
  app.add_option("--png-compression", flags.pngCompression,
                 "override the request's PNG zlib level: 0 (fastest) .. 9 (smallest)")
      ->check(CLI::Range(0, 9));
  app.add_option("--size", flags.size,
                 "image size: N (square) or WxH; a model's thumbnail is 256 by default")
      ->check([](const std::string& text) {
        return lgh::cli::parseImageSize(text) ? std::string()
                                              : std::string("must be N or WxH, each 1..16384");
      });
  auto* viewOption =
      app.add_option("--view", flags.view,
                     "a model's view: iso (the default), front, side, top, or a direction X,Y,Z "
                     "from the model towards the camera")
          ->check([](const std::string& text) {
            return lgh::cli::parseViewDirection(text)
                       ? std::string()
                       : std::string("must be iso, front, side, top or X,Y,Z (not all zero)");
          });
  app.add_flag("--transparent", flags.transparent,
               "leave the background transparent (alpha 0 where nothing was drawn)");
  app.add_flag("-q,--quiet", flags.quiet, "print nothing on success");
  app.add_option("--repeat", flags.repeat,
                 "render N times, frames 2..N back to back as lghd renders them (the GPU busy "
                 "while frames are read back and encoded); timings are the per-pass medians of "
                 "the warm frames 2..N")
      ->check(CLI::Range(1, 10000));
  app.add_option("--encode-threads", flags.encodeThreads,
                 "threads encoding frames; a large PNG's deflate strips use the idle ones too. "
                 "0: one per hardware thread")
      ->check(CLI::Range(0, 1024));
  lgh::cli::addContextFlags(app, flags.context);
  CLI11_PARSE(app, argc, argv);
  if (flags.requestPath.empty() && !flags.demo) {
    std::cerr << "lgh-render: give a request file, a .glb/.gltf model or --demo (see --help)\n";
    return 2;
  }
  const bool model = !flags.demo && lgh::cli::isModelFile(flags.requestPath);
  if (viewOption->count() > 0 && !model) {
    std::cerr << "lgh-render: --view frames a model: give a .glb or .gltf file\n";
    return 2;
  }
  if (model && app.count("--asset-root") > 0) {
    std::cerr << "lgh-render: a model's folder is its asset root: leave out --asset-root\n";
    return 2;
  }
  lgh::cli::setUpLogging(flags.context.logLevel);
  try {
    return run(flags);
  } catch (const lgh::Error& error) {
    std::cerr << "lgh-render: error (" << lgh::errorCodeName(error.code()) << "): " << error.what()
              << '\n';
    return 1;
  } catch (const std::exception& error) {
    std::cerr << "lgh-render: error: " << error.what() << '\n';
    return 1;
  }
} catch (const std::exception& error) {
  std::cerr << "lgh-render: error: " << error.what() << '\n';
  return 1;
} catch (...) {
  std::cerr << "lgh-render: unknown error\n";
  return 1;
}
