#include "lgh/bench/png_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <png.h>
#include <zlib.h>
#include <nlohmann/json.hpp>
#if LGH_BENCH_SPNG
#include <spng.h>
#endif

#include "image/png_writer.hpp"
#include "lgh/error.hpp"
#include "lgh/renderer.hpp"
#include "lgh/task_pool.hpp"

namespace lgh::bench {
namespace {

using Bytes = std::vector<std::uint8_t>;

// ---- libpng, as both backends wrote PNGs before issue 18 ----

void appendBytes(png_structp png, png_bytep data, std::size_t length) {
  auto* out = static_cast<Bytes*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + length);
}
void flushNothing(png_structp /*png*/) {}

Bytes libpngEncode(const Image8& image, int level, int strategy, int filters) {
  Bytes out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw Error(ErrorCode::Internal, "libpng failed in the benchmark");
  }
  png_set_write_fn(png, &out, appendBytes, flushNothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8,
               image.channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, level);
  png_set_compression_strategy(png, strategy);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, filters);
  png_write_info(png, info);
  const std::size_t rowBytes = static_cast<std::size_t>(image.width) * image.channels;
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (std::size_t y = 0; y < rows.size(); ++y) {
    rows[y] = const_cast<png_bytep>(&image.pixels[y * rowBytes]);
  }
  png_write_image(png, rows.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return out;
}

#if LGH_BENCH_SPNG
Bytes spngEncode(const Image8& image, int level) {
  std::unique_ptr<spng_ctx, void (*)(spng_ctx*)> context(spng_ctx_new(SPNG_CTX_ENCODER),
                                                         spng_ctx_free);
  spng_set_option(context.get(), SPNG_ENCODE_TO_BUFFER, 1);
  spng_set_option(context.get(), SPNG_IMG_COMPRESSION_LEVEL, level);
  spng_ihdr header{};
  header.width = static_cast<std::uint32_t>(image.width);
  header.height = static_cast<std::uint32_t>(image.height);
  header.bit_depth = 8;
  header.color_type =
      image.channels == 4 ? SPNG_COLOR_TYPE_TRUECOLOR_ALPHA : SPNG_COLOR_TYPE_TRUECOLOR;
  spng_set_ihdr(context.get(), &header);
  const int status = spng_encode_image(context.get(), image.pixels.data(), image.pixels.size(),
                                       SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
  if (status != 0) throw Error(ErrorCode::Internal, fmt::format("spng: {}", spng_strerror(status)));
  std::size_t length = 0;
  int error = 0;
  void* buffer = spng_get_png_buffer(context.get(), &length, &error);
  Bytes out(static_cast<std::uint8_t*>(buffer), static_cast<std::uint8_t*>(buffer) + length);
  std::free(buffer);
  return out;
}
#endif

struct Candidate {
  std::string name;
  bool threaded = false;  // runs at each thread count; otherwise at one
  std::function<Bytes(const Image8&, int level, TaskPool* pool, int threads)> encode;
};

Bytes writer(const Image8& image, int level, TaskPool* pool, image_io::detail::DeflateMode mode,
             int strips) {
  const Image8View view{image.width, image.height, image.channels, image.pixels.data()};
  return image_io::detail::writePng(view, {}, {level, pool, mode, strips});
}

std::vector<Candidate> candidates() {
  using image_io::detail::DeflateMode;
  std::vector<Candidate> list = {
    {"libpng", false,
     [](const Image8& image, int level, TaskPool*, int) {
       return libpngEncode(image, level, Z_DEFAULT_STRATEGY, PNG_ALL_FILTERS);
     }},
    {"libpng-filtered", false,
     [](const Image8& image, int level, TaskPool*, int) {
       return libpngEncode(image, level, Z_FILTERED, PNG_ALL_FILTERS);
     }},
    {"libpng-rle", false,
     [](const Image8& image, int level, TaskPool*, int) {
       return libpngEncode(image, level, Z_RLE, PNG_ALL_FILTERS);
     }},
    {"libpng-up", false,
     [](const Image8& image, int level, TaskPool*, int) {
       return libpngEncode(image, level, Z_DEFAULT_STRATEGY, PNG_FILTER_UP);
     }},
#if LGH_BENCH_SPNG
    {"spng", false,
     [](const Image8& image, int level, TaskPool*, int) { return spngEncode(image, level); }},
#endif
    {"zlib", false,
     [](const Image8& image, int level, TaskPool*, int) {
       return writer(image, level, nullptr, DeflateMode::Strips, 1);
     }},
    {"libdeflate", true,
     [](const Image8& image, int level, TaskPool* pool, int) {
       return writer(image, level, pool, DeflateMode::Whole, 0);
     }},
    {"strips", true,
     [](const Image8& image, int level, TaskPool* pool, int threads) {
       return writer(image, level, pool, DeflateMode::Strips, 2 * threads);
     }},
    {"auto", true,
     [](const Image8& image, int level, TaskPool* pool, int) {
       return image_io::encodePng(image, {}, level, pool);
     }},
  };
  return list;
}

Image8 renderDemo(Renderer& renderer, int width, int height) {
  RenderRequest request;
  request.output.width = width;
  request.output.height = height;
  return renderer.renderFrame(request).pixels.toImage8();
}

PngEncoderRun measure(const Candidate& candidate, const Image8& image, int level, int threads,
                      int repeat) {
  // `threads` in all: this thread and threads - 1 workers.
  std::optional<TaskPool> pool;
  if (threads > 1) pool.emplace(threads - 1);
  TaskPool* workers = pool ? &*pool : nullptr;
  std::vector<double> times;
  Bytes bytes;
  for (int i = 0; i < std::max(repeat, 1); ++i) {
    const auto start = std::chrono::steady_clock::now();
    bytes = candidate.encode(image, level, workers, threads);
    times.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  std::sort(times.begin(), times.end());
  PngEncoderRun run;
  run.image = fmt::format("{}x{}", image.width, image.height);
  run.encoder = candidate.name;
  run.level = level;
  run.threads = threads;
  run.medianMs = times[times.size() / 2];
  run.minMs = times.front();
  run.bytes = bytes.size();
  const image_io::Decoded decoded = image_io::decode(bytes, candidate.name);
  run.pixelsMatch = decoded.width == image.width && decoded.height == image.height &&
                    decoded.channels == image.channels && decoded.pixels8 == image.pixels;
  return run;
}

}  // namespace

PngBenchmarkResult runPngBenchmark(const PngBenchmarkOptions& options) {
  Renderer renderer(options.renderer);
  PngBenchmarkResult result;
  result.device = renderer.device();
  const std::vector<Candidate> all = candidates();
  for (const Candidate& candidate : all) result.encoders.push_back(candidate.name);
  for (const auto& [width, height] : options.sizes) {
    const Image8 image = renderDemo(renderer, width, height);
    for (const Candidate& candidate : all) {
      if (!options.encoders.empty() && std::find(options.encoders.begin(), options.encoders.end(),
                                                 candidate.name) == options.encoders.end()) {
        continue;
      }
      for (const int level : options.levels) {
        if (!candidate.threaded) {
          result.runs.push_back(measure(candidate, image, level, 1, options.repeat));
          continue;
        }
        for (const int threads : options.threads) {
          result.runs.push_back(measure(candidate, image, level, threads, options.repeat));
        }
      }
    }
  }
  return result;
}

void to_json(nlohmann::json& json, const PngBenchmarkResult& result) {
  json = {{"benchmark", "png"},
          {"device", result.device.toJson()},
          {"encoders", result.encoders},
          {"runs", nlohmann::json::array()}};
  for (const PngEncoderRun& run : result.runs) {
    json["runs"].push_back({{"image", run.image},
                            {"encoder", run.encoder},
                            {"level", run.level},
                            {"threads", run.threads},
                            {"median_ms", run.medianMs},
                            {"min_ms", run.minMs},
                            {"bytes", run.bytes},
                            {"pixels_match", run.pixelsMatch}});
  }
}

}  // namespace lgh::bench
