#include "image/png_filters.hpp"

#include <array>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace lgh::image_io::detail {
namespace {

// The filters' loops vectorise; on x86-64 a second copy for AVX2 is picked at load time where the
// CPU has it, the build's baseline being SSE2 (docs/BENCHMARKS.md).
#if defined(__x86_64__) && defined(__GNUC__)
#define LGH_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define LGH_VECTOR_CLONES
#endif

enum Filter : std::uint8_t { kNone = 0, kSub = 1, kUp = 2, kAverage = 3, kPaeth = 4 };

LGH_VECTOR_CLONES
std::uint32_t cost(const std::uint8_t* row, std::size_t n) {
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    // The byte read as signed, its absolute value: 0..127 as is, 128..255 as 256 - byte.
    const std::uint32_t value = row[i];
    sum += value < 128U ? value : 256U - value;
  }
  return sum;
}

LGH_VECTOR_CLONES
void sub(const std::uint8_t* x, std::size_t n, int bpp, std::uint8_t* out) {
  for (int i = 0; i < bpp; ++i) out[i] = x[i];
  for (std::size_t i = static_cast<std::size_t>(bpp); i < n; ++i) {
    out[i] = static_cast<std::uint8_t>(x[i] - x[i - bpp]);
  }
}

LGH_VECTOR_CLONES
void up(const std::uint8_t* x, const std::uint8_t* prior, std::size_t n, std::uint8_t* out) {
  for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<std::uint8_t>(x[i] - prior[i]);
}

LGH_VECTOR_CLONES
void average(const std::uint8_t* x, const std::uint8_t* prior, std::size_t n, int bpp,
             std::uint8_t* out) {
  for (int i = 0; i < bpp; ++i) out[i] = static_cast<std::uint8_t>(x[i] - (prior[i] >> 1));
  for (std::size_t i = static_cast<std::size_t>(bpp); i < n; ++i) {
    out[i] = static_cast<std::uint8_t>(x[i] - ((x[i - bpp] + prior[i]) >> 1));
  }
}

// Branch-free, so that the compiler vectorises it.
LGH_VECTOR_CLONES
void paeth(const std::uint8_t* x, const std::uint8_t* prior, std::size_t n, int bpp,
           std::uint8_t* out) {
  for (int i = 0; i < bpp; ++i) out[i] = static_cast<std::uint8_t>(x[i] - prior[i]);
  for (std::size_t i = static_cast<std::size_t>(bpp); i < n; ++i) {
    const int a = x[i - bpp];
    const int b = prior[i];
    const int c = prior[i - bpp];
    const int pa = std::abs(b - c);
    const int pb = std::abs(a - c);
    const int pc = std::abs(a + b - 2 * c);
    const int bc = pb <= pc ? b : c;
    const int predictor = (pa <= pb && pa <= pc) ? a : bc;
    out[i] = static_cast<std::uint8_t>(x[i] - predictor);
  }
}

}  // namespace

void filterRows(const std::uint8_t* image, std::size_t rowBytes, int bytesPerPixel, int firstRow,
                int endRow, bool adaptive, std::uint8_t* out) {
  const std::vector<std::uint8_t> zeroRow(adaptive ? rowBytes : 0, 0);
  std::array<std::vector<std::uint8_t>, 5> candidates;
  if (adaptive) {
    for (std::size_t f = kSub; f <= kPaeth; ++f) candidates[f].resize(rowBytes);
  }
  for (int y = firstRow; y < endRow; ++y) {
    const std::uint8_t* row = image + static_cast<std::size_t>(y) * rowBytes;
    std::uint8_t* target = out + static_cast<std::size_t>(y - firstRow) * (rowBytes + 1);
    if (!adaptive) {
      target[0] = kNone;
      std::memcpy(target + 1, row, rowBytes);
      continue;
    }
    const std::uint8_t* prior = y > 0 ? row - rowBytes : zeroRow.data();
    sub(row, rowBytes, bytesPerPixel, candidates[kSub].data());
    up(row, prior, rowBytes, candidates[kUp].data());
    average(row, prior, rowBytes, bytesPerPixel, candidates[kAverage].data());
    paeth(row, prior, rowBytes, bytesPerPixel, candidates[kPaeth].data());
    std::uint8_t best = kNone;
    std::uint32_t bestCost = cost(row, rowBytes);
    for (std::uint8_t f = kSub; f <= kPaeth; ++f) {
      const std::uint32_t c = cost(candidates[f].data(), rowBytes);
      if (c < bestCost) {
        bestCost = c;
        best = f;
      }
    }
    target[0] = best;
    std::memcpy(target + 1, best == kNone ? row : candidates[best].data(), rowBytes);
  }
}

}  // namespace lgh::image_io::detail
