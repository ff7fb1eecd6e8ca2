#include "image/png_writer.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <string_view>

#include <fmt/format.h>
#include <libdeflate.h>
#include <zlib.h>

#include "image/image_common.hpp"
#include "image/png_filters.hpp"
#include "lgh/error.hpp"

namespace lgh::image_io::detail {
namespace {

// IDAT chunks are cut at this size: any size up to 2^31 - 1 is valid, but readers that buffer a
// whole chunk (some do) stay small.
constexpr std::size_t kIdatChunkBytes = 1 << 20;
// Below this much filtered data an image is deflated whole: strips would save little time and
// lose compression at each join.
constexpr std::size_t kMinStripBytes = std::size_t{256} * 1024;
// A strip holds at least this many rows.
constexpr int kMinStripRows = 16;
// Rows filtered per task when filtering in parallel ahead of a whole deflate.
constexpr int kFilterRowsPerTask = 64;

// How much slower zlib deflates than libdeflate at the same level, measured on the demo at
// 1280x720 (docs/BENCHMARKS.md, "PNG encoder"). Strips (zlib) pay off only with more than this
// many threads: twice as many are asked for, so that they win clearly.
int zlibSlowdown(int level) { return level <= 1 ? 10 : 4; }

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    out_.insert(out_.end(), p, p + size);
  }
  void u32(std::uint32_t value) {
    const std::array<std::uint8_t, 4> big = {
        static_cast<std::uint8_t>(value >> 24), static_cast<std::uint8_t>(value >> 16),
        static_cast<std::uint8_t>(value >> 8), static_cast<std::uint8_t>(value)};
    bytes(big.data(), big.size());
  }
  void chunk(std::string_view type, const std::uint8_t* data, std::size_t size) {
    u32(static_cast<std::uint32_t>(size));
    const std::size_t typeAt = out_.size();
    bytes(type.data(), 4);
    if (size > 0) bytes(data, size);
    u32(static_cast<std::uint32_t>(
        crc32(0, out_.data() + typeAt, static_cast<uInt>(out_.size() - typeAt))));
  }

 private:
  std::vector<std::uint8_t>& out_;
};

std::uint8_t colorType(int channels) {
  switch (channels) {
    case 1:
      return 0;  // grey
    case 2:
      return 4;  // grey + alpha
    case 3:
      return 2;  // RGB
    default:
      return 6;  // RGBA
  }
}

void writeHeader(ByteWriter& out, const Image8View& image) {
  static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  out.bytes(kSignature, sizeof kSignature);
  std::array<std::uint8_t, 13> ihdr{};
  for (int i = 0; i < 4; ++i) {
    ihdr[i] = static_cast<std::uint8_t>(static_cast<std::uint32_t>(image.width) >> (24 - 8 * i));
    ihdr[4 + i] =
        static_cast<std::uint8_t>(static_cast<std::uint32_t>(image.height) >> (24 - 8 * i));
  }
  ihdr[8] = 8;  // bit depth
  ihdr[9] = colorType(image.channels);
  // compression 0 (deflate), filter method 0 (adaptive), interlace 0: already zero.
  out.chunk("IHDR", ihdr.data(), ihdr.size());
}

void writeText(ByteWriter& out, const ImageMetadata& metadata) {
  std::vector<std::uint8_t> data;
  for (const auto& [key, value] : metadata) {
    data.assign(key.begin(), key.end());
    data.push_back(0);
    data.insert(data.end(), value.begin(), value.end());
    out.chunk("tEXt", data.data(), data.size());
  }
}

void writeImageData(ByteWriter& out, const std::vector<std::uint8_t>& zlibStream) {
  for (std::size_t at = 0; at < zlibStream.size(); at += kIdatChunkBytes) {
    out.chunk("IDAT", zlibStream.data() + at, std::min(kIdatChunkBytes, zlibStream.size() - at));
  }
}

std::size_t filteredBytes(const Image8View& image) {
  return (static_cast<std::size_t>(image.width) * image.channels + 1) *
         static_cast<std::size_t>(image.height);
}

// The filtered rows of the whole image, filtered in row blocks on the pool.
std::vector<std::uint8_t> filterImage(const Image8View& image, bool adaptive, TaskPool* pool) {
  const std::size_t rowBytes = static_cast<std::size_t>(image.width) * image.channels;
  std::vector<std::uint8_t> filtered(filteredBytes(image));
  const auto blocks =
      static_cast<std::size_t>((image.height + kFilterRowsPerTask - 1) / kFilterRowsPerTask);
  auto filterBlock = [&](std::size_t block) {
    const int first = static_cast<int>(block) * kFilterRowsPerTask;
    const int end = std::min(image.height, first + kFilterRowsPerTask);
    filterRows(image.pixels, rowBytes, image.channels, first, end, adaptive,
               filtered.data() + static_cast<std::size_t>(first) * (rowBytes + 1));
  };
  if (pool != nullptr && blocks > 1 && pool->idleWorkers() > 0) {
    pool->parallelFor(blocks, filterBlock);
  } else {
    for (std::size_t block = 0; block < blocks; ++block) filterBlock(block);
  }
  return filtered;
}

struct CompressorFree {
  void operator()(libdeflate_compressor* compressor) const {
    libdeflate_free_compressor(compressor);
  }
};

std::vector<std::uint8_t> deflateWhole(const std::vector<std::uint8_t>& filtered, int level) {
  const std::unique_ptr<libdeflate_compressor, CompressorFree> compressor(
      libdeflate_alloc_compressor(level));
  if (!compressor) throw Error(ErrorCode::Internal, "libdeflate could not allocate a compressor");
  std::vector<std::uint8_t> stream(
      libdeflate_zlib_compress_bound(compressor.get(), filtered.size()));
  const std::size_t size = libdeflate_zlib_compress(compressor.get(), filtered.data(),
                                                    filtered.size(), stream.data(), stream.size());
  if (size == 0) throw Error(ErrorCode::Internal, "libdeflate could not compress the image");
  stream.resize(size);
  return stream;
}

// One strip of rows: filtered, then raw-deflated by its own zlib stream, ended by a full flush
// (byte-aligned, BFINAL clear) or, for the last strip, by the final block.
struct Strip {
  int firstRow = 0;
  int endRow = 0;
  std::vector<std::uint8_t> deflated;
  uLong adler = 1;
  std::size_t inputBytes = 0;
};

class ZStream {
 public:
  explicit ZStream(int level) {
    if (deflateInit2(&stream_, level, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
      throw Error(ErrorCode::Internal, "zlib could not start a deflate stream");
    }
  }
  ~ZStream() { deflateEnd(&stream_); }
  ZStream(const ZStream&) = delete;
  ZStream& operator=(const ZStream&) = delete;
  z_stream* get() { return &stream_; }

 private:
  z_stream stream_{};
};

void deflateStrip(const Image8View& image, int level, bool last, Strip& strip) {
  const std::size_t rowBytes = static_cast<std::size_t>(image.width) * image.channels;
  std::vector<std::uint8_t> filtered(static_cast<std::size_t>(strip.endRow - strip.firstRow) *
                                     (rowBytes + 1));
  filterRows(image.pixels, rowBytes, image.channels, strip.firstRow, strip.endRow, true,
             filtered.data());
  strip.inputBytes = filtered.size();
  strip.adler = adler32(1, filtered.data(), static_cast<uInt>(filtered.size()));
  ZStream zlib(level);
  z_stream* z = zlib.get();
  // deflateBound covers the stream's end; a full flush adds at most 5 bytes of marker, plus 6.
  strip.deflated.resize(deflateBound(z, filtered.size()) + 16);
  z->next_in = filtered.data();
  z->avail_in = static_cast<uInt>(filtered.size());
  z->next_out = strip.deflated.data();
  z->avail_out = static_cast<uInt>(strip.deflated.size());
  const int result = deflate(z, last ? Z_FINISH : Z_FULL_FLUSH);
  if ((last && result != Z_STREAM_END) || (!last && (result != Z_OK || z->avail_in != 0))) {
    throw Error(ErrorCode::Internal, fmt::format("zlib could not deflate rows {}..{} (status {})",
                                                 strip.firstRow, strip.endRow, result));
  }
  strip.deflated.resize(z->total_out);
}

// zlib header for a 32 KiB window at `level` (RFC 1950: FLEVEL, and FCHECK making it a
// multiple of 31).
std::array<std::uint8_t, 2> zlibHeader(int level) {
  const int flevel = level <= 1 ? 0 : level <= 5 ? 1 : level == 6 ? 2 : 3;
  const int cmf = 0x78;
  int flg = flevel << 6;
  flg += 31 - ((cmf * 256 + flg) % 31);
  return {static_cast<std::uint8_t>(cmf), static_cast<std::uint8_t>(flg)};
}

std::vector<std::uint8_t> deflateStrips(const Image8View& image, int level, int stripCount,
                                        TaskPool* pool) {
  const int count = std::clamp(stripCount, 1, std::max(1, image.height / kMinStripRows));
  std::vector<Strip> strips(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    strips[i].firstRow = static_cast<int>(static_cast<long long>(image.height) * i / count);
    strips[i].endRow = static_cast<int>(static_cast<long long>(image.height) * (i + 1) / count);
  }
  auto run = [&](std::size_t i) { deflateStrip(image, level, i + 1 == strips.size(), strips[i]); };
  if (pool != nullptr) {
    pool->parallelFor(strips.size(), run);
  } else {
    for (std::size_t i = 0; i < strips.size(); ++i) run(i);
  }
  std::vector<std::uint8_t> stream;
  std::size_t total = 6;
  for (const Strip& strip : strips) total += strip.deflated.size();
  stream.reserve(total);
  const auto header = zlibHeader(level);
  stream.insert(stream.end(), header.begin(), header.end());
  uLong adler = 1;
  for (const Strip& strip : strips) {
    stream.insert(stream.end(), strip.deflated.begin(), strip.deflated.end());
    adler = adler32_combine(adler, strip.adler, static_cast<z_off_t>(strip.inputBytes));
  }
  for (int shift = 24; shift >= 0; shift -= 8) {
    stream.push_back(static_cast<std::uint8_t>(adler >> shift));
  }
  return stream;
}

}  // namespace

bool prefersStrips(const Image8View& image, int level, int threads) {
  return level > 0 && filteredBytes(image) >= kMinStripBytes && threads >= 2 * zlibSlowdown(level);
}

std::vector<std::uint8_t> writePng(const Image8View& image, const ImageMetadata& metadata,
                                   const PngWriteOptions& options) {
  const int level = options.level;
  DeflateMode mode = options.mode;
  int threads = 1;
  if (options.pool != nullptr) threads += options.pool->idleWorkers();
  if (mode == DeflateMode::Auto) {
    mode = prefersStrips(image, level, threads) ? DeflateMode::Strips : DeflateMode::Whole;
  }
  std::vector<std::uint8_t> stream;
  if (mode == DeflateMode::Strips) {
    const int strips = options.strips > 0 ? options.strips : 2 * threads;
    stream = deflateStrips(image, level, strips, options.pool);
  } else {
    // Level 0 stores the rows: filtering them would only cost time.
    stream = deflateWhole(filterImage(image, level > 0, options.pool), level);
  }
  std::vector<std::uint8_t> png;
  png.reserve(stream.size() + 1024);
  ByteWriter out(png);
  writeHeader(out, image);
  writeText(out, metadata);
  writeImageData(out, stream);
  out.chunk("IEND", nullptr, 0);
  return png;
}

}  // namespace lgh::image_io::detail

namespace lgh::image_io {

std::vector<std::uint8_t> encodePng(const Image8View& image, const ImageMetadata& metadata,
                                    int compressionLevel, TaskPool* pool) {
  detail::checkImage8View(image);
  detail::checkPngCompression(compressionLevel);
  detail::checkMetadata(metadata, detail::MetadataFormat::Png);
  return detail::writePng(image, metadata, {compressionLevel, pool});
}

std::vector<std::uint8_t> encodePng(const Image8& image, const ImageMetadata& metadata,
                                    int compressionLevel, TaskPool* pool) {
  detail::checkImage8(image);
  return encodePng(Image8View{image.width, image.height, image.channels, image.pixels.data()},
                   metadata, compressionLevel, pool);
}

}  // namespace lgh::image_io
