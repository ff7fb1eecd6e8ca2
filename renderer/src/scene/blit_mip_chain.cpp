#include "scene/blit_mip_chain.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include "image/image_common.hpp"

namespace lgh {
namespace {

// The rounded mean of two bytes in each 16-bit lane of `a` and `b` (the low bytes).
std::uint32_t halvesRoundedUp(std::uint32_t a, std::uint32_t b) {
  return ((a + b + 0x00010001U) >> 1) & 0x00FF00FFU;
}

// The texels of one output row from source rows `top` and `bottom`: each the mean of two
// neighbouring texels of each (the same texel twice where the row is one texel wide).
void halveRow(const std::uint8_t* top, const std::uint8_t* bottom, int width, bool srgb,
              std::uint8_t* out) {
  const std::array<float, 256>& toLinear = image_io::detail::srgbToLinearTable();
  const std::size_t step = width > 1 ? 4 : 0;  // from a texel to its right neighbour
  const auto outWidth = static_cast<std::size_t>(std::max(width / 2, 1));
  // Every channel's mean as llvmpipe's blit to half size takes it: a rounded mean of each row's
  // two texels, then of the two rows' (rounded half up each time; tests/unit/test_mip_chain.cpp).
  // Two channels at a time, in the 16-bit lanes of a word.
  for (std::size_t x = 0; x < outWidth; ++x) {
    std::array<std::uint32_t, 4> texels{};
    std::memcpy(&texels[0], top + 8 * x, 4);
    std::memcpy(&texels[1], top + 8 * x + step, 4);
    std::memcpy(&texels[2], bottom + 8 * x, 4);
    std::memcpy(&texels[3], bottom + 8 * x + step, 4);
    std::uint32_t mean = 0;
    for (const int shift : {0, 8}) {
      const auto lanes = [shift](std::uint32_t t) { return (t >> shift) & 0x00FF00FFU; };
      const std::uint32_t upper = halvesRoundedUp(lanes(texels[0]), lanes(texels[1]));
      const std::uint32_t lower = halvesRoundedUp(lanes(texels[2]), lanes(texels[3]));
      mean |= halvesRoundedUp(upper, lower) << shift;
    }
    std::memcpy(out + 4 * x, &mean, 4);
  }
  if (!srgb) return;
  for (std::size_t x = 0; x < outWidth; ++x) {  // colour in linear light, alpha rounded half up
    const std::uint8_t* a = top + 8 * x;
    const std::uint8_t* b = bottom + 8 * x;
    for (std::size_t c = 0; c < 3; ++c) {
      const float sum =
          toLinear[a[c]] + toLinear[a[c + step]] + toLinear[b[c]] + toLinear[b[c + step]];
      out[4 * x + c] = image_io::detail::srgbCode(std::clamp(sum * 0.25F, 0.0F, 1.0F));
    }
    out[4 * x + 3] = static_cast<std::uint8_t>((a[3] + a[3 + step] + b[3] + b[3 + step] + 2) / 4);
  }
}

// Where output texel `i` of `outSize` samples a source of `size` texels by bilinear filtering at
// its centre: the two source texels and the second one's weight.
struct Tap {
  int first = 0;
  int second = 0;
  float weight = 0.0F;
};
Tap tapFor(int i, int size, int outSize) {
  const float at =
      (static_cast<float>(i) + 0.5F) * static_cast<float>(size) / static_cast<float>(outSize) -
      0.5F;
  const float floor = std::floor(at);
  Tap tap;
  tap.first = std::clamp(static_cast<int>(floor), 0, size - 1);
  tap.second = std::clamp(static_cast<int>(floor) + 1, 0, size - 1);
  tap.weight = at - floor;
  return tap;
}

// A level below one with an odd side (above 1): each texel sampled bilinearly at its centre, as a
// GPU's blit to half size does (glGenerateMipmap), in linear light for sRGB colour.
Image8 resampled(const Image8& previous, Image8 next, bool srgb) {
  const std::array<float, 256>& toLinear = image_io::detail::srgbToLinearTable();
  const auto value = [&](int x, int y, int c) {
    const std::uint8_t code =
        previous.pixels[(static_cast<std::size_t>(y) * previous.width + x) * 4 + c];
    return srgb && c < 3 ? toLinear[code] : static_cast<float>(code) / 255.0F;
  };
  for (int y = 0; y < next.height; ++y) {
    const Tap ty = tapFor(y, previous.height, next.height);
    for (int x = 0; x < next.width; ++x) {
      const Tap tx = tapFor(x, previous.width, next.width);
      std::uint8_t* out = &next.pixels[(static_cast<std::size_t>(y) * next.width + x) * 4];
      for (int c = 0; c < 4; ++c) {
        const float top =
            std::lerp(value(tx.first, ty.first, c), value(tx.second, ty.first, c), tx.weight);
        const float bottom =
            std::lerp(value(tx.first, ty.second, c), value(tx.second, ty.second, c), tx.weight);
        const float mean = std::lerp(top, bottom, ty.weight);
        out[c] =
            srgb && c < 3
                ? image_io::detail::srgbCode(std::clamp(mean, 0.0F, 1.0F))
                : static_cast<std::uint8_t>(std::lround(std::clamp(mean, 0.0F, 1.0F) * 255.0F));
      }
    }
  }
  return next;
}

// One level below `previous`: each texel the mean of a 2x2 block, rounded as llvmpipe's blit
// rounds data (halveRow) and to the nearest code in linear light for sRGB colour; where a side is
// odd, bilinear samples at the texels' centres (`resampled`), so that the levels stay aligned.
Image8 halved(const Image8& previous, bool srgb) {
  Image8 next;
  next.width = std::max(previous.width / 2, 1);
  next.height = std::max(previous.height / 2, 1);
  next.channels = 4;
  next.pixels.resize(static_cast<std::size_t>(next.width) * next.height * 4);
  const auto odd = [](int size) { return size > 1 && size % 2 != 0; };
  if (odd(previous.width) || odd(previous.height)) {
    return resampled(previous, std::move(next), srgb);
  }
  const std::size_t rowBytes = static_cast<std::size_t>(previous.width) * 4;
  for (int y = 0; y < next.height; ++y) {
    const int top = std::min(2 * y, previous.height - 1);
    const int bottom = std::min(2 * y + 1, previous.height - 1);
    halveRow(&previous.pixels[static_cast<std::size_t>(top) * rowBytes],
             &previous.pixels[static_cast<std::size_t>(bottom) * rowBytes], previous.width, srgb,
             &next.pixels[static_cast<std::size_t>(y) * next.width * 4]);
  }
  return next;
}

}  // namespace

std::vector<Image8> buildBlitMipChain(const Image8& image, bool srgb) {
  std::vector<Image8> chain;
  const Image8* previous = &image;
  while (previous->width > 1 || previous->height > 1) {
    chain.push_back(halved(*previous, srgb));
    previous = &chain.back();
  }
  return chain;
}

}  // namespace lgh
