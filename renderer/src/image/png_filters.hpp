// PNG row filtering (PNG spec section 9): each row gets the filter whose output has the smallest
// sum of absolute (signed) bytes, the heuristic libpng uses with all five filters. Kept in a file
// of its own, built with -O3, so the per-byte loops are vectorised in every configuration.
#pragma once

#include <cstddef>
#include <cstdint>

namespace lgh::image_io::detail {

// Writes rows [firstRow, endRow) of an 8-bit image (rows `rowBytes` apart, `bytesPerPixel` of
// 1..4) to `out` as PNG filtered rows: a filter-type byte, then rowBytes filtered bytes, each row
// rowBytes + 1 apart starting at out[0]. `adaptive` false writes every row unfiltered (type 0).
void filterRows(const std::uint8_t* image, std::size_t rowBytes, int bytesPerPixel, int firstRow,
                int endRow, bool adaptive, std::uint8_t* out);

}  // namespace lgh::image_io::detail
