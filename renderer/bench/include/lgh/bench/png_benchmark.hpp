// The PNG encoder benchmark behind `lgh-bench png`: the demo rendered once per size (the GPU's
// display codes, as lghd encodes them), then encoded by each candidate at each zlib level, timed
// on the CPU, sized, and decoded again to check the pixels. The candidates (docs/BENCHMARKS.md,
// "PNG encoder"):
//   libpng           the encoder before issue 18: libpng, all five filters, zlib's default strategy
//   libpng-filtered  the same with zlib's Z_FILTERED strategy
//   libpng-rle       the same with Z_RLE
//   libpng-up        libpng with the Up filter only
//   spng             libspng with its defaults (when built with it)
//   zlib             our filters, zlib over the whole image (one strip), one thread
//   libdeflate       our filters, libdeflate over the whole image; rows filtered on `threads`
//   strips           our filters, zlib strips on `threads`, joined with full flushes
//   auto             what lghd does with `threads` idle (image_io::encodePng with a pool)
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "lgh/device_info.hpp"
#include "lgh/renderer_options.hpp"

namespace lgh::bench {

struct PngBenchmarkOptions {
  RendererOptions renderer;
  std::vector<std::pair<int, int>> sizes = {{1280, 720}, {256, 256}};
  std::vector<int> levels = {1, 6, 9};
  std::vector<int> threads = {1};     // thread counts for libdeflate, strips and auto
  std::vector<std::string> encoders;  // empty: all
  int repeat = 5;                     // timed encodes per run (the median is kept)
};

struct PngEncoderRun {
  std::string image;  // "1280x720"
  std::string encoder;
  int level = 0;
  int threads = 1;
  double medianMs = 0.0;
  double minMs = 0.0;
  std::size_t bytes = 0;
  bool pixelsMatch = false;  // decoded again (this build's backend) to the same pixels
};

struct PngBenchmarkResult {
  DeviceInfo device;
  std::vector<std::string> encoders;  // the candidates built in
  std::vector<PngEncoderRun> runs;
};

PngBenchmarkResult runPngBenchmark(const PngBenchmarkOptions& options);
void to_json(nlohmann::json& json, const PngBenchmarkResult& result);

}  // namespace lgh::bench
