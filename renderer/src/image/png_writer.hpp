// The PNG encoder of both image backends (docs/IMAGES.md, "PNG encoder"): rows filtered as libpng
// does (all five filters, smallest sum of absolute bytes), deflated by libdeflate in one piece, or,
// for a large image with idle workers, in parallel row strips by zlib joined with full flushes
// into one zlib stream (as pigz does). The choice follows docs/BENCHMARKS.md ("PNG encoder").
// The result is a standard PNG: IHDR, tEXt, IDAT, IEND.
#pragma once

#include <cstdint>
#include <vector>

#include "lgh/image.hpp"
#include "lgh/task_pool.hpp"

namespace lgh::image_io::detail {

enum class DeflateMode {
  Auto,    // strips when the image is large and enough workers are idle, else whole
  Whole,   // libdeflate over the whole image on the calling thread
  Strips,  // zlib strips on `pool` (or serially without one)
};

struct PngWriteOptions {
  int level = kDefaultPngCompression;  // zlib's scale, 0 (stored) .. 9
  TaskPool* pool = nullptr;            // workers for filtering and strips; null: this thread only
  DeflateMode mode = DeflateMode::Auto;
  int strips = 0;  // Strips: how many (0: from the pool's size)
};

// Expects a checked image (checkImage8View) and checked metadata.
std::vector<std::uint8_t> writePng(const Image8View& image, const ImageMetadata& metadata,
                                   const PngWriteOptions& options);

// Whether Auto deflates `image` in strips at `level` with `threads` threads free.
bool prefersStrips(const Image8View& image, int level, int threads);

}  // namespace lgh::image_io::detail
