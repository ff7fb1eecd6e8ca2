// The PNG encoder (renderer/src/image/png_writer.hpp): whole images deflated by libdeflate, and
// large ones in parallel row strips by zlib joined with full flushes into one zlib stream. Every
// way of writing must be a standard PNG that decodes to the same pixels with libpng directly, with
// this build's image backend (OpenImageIO in the default build, libpng in the lean one), and with
// zlib inflating the joined stream whole (its Adler-32 checked).
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <png.h>
#include <zlib.h>

#include "image/png_writer.hpp"
#include "lgh/image.hpp"
#include "lgh/task_pool.hpp"

namespace {

using lgh::image_io::detail::DeflateMode;
using Bytes = std::vector<std::uint8_t>;

// Smooth gradients (what renders look like), noise, and flat areas: every filter gets chosen.
lgh::Image8 testImage(int width, int height, int channels) {
  lgh::Image8 image{width, height, channels, {}};
  image.pixels.resize(static_cast<std::size_t>(width) * height * channels);
  std::mt19937 random(11);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < channels; ++c) {
        std::uint8_t value = 0;
        if (y < height / 3) {
          value = static_cast<std::uint8_t>((x * 255 / width + c * 40) & 0xFF);
        } else if (y < 2 * height / 3) {
          value = static_cast<std::uint8_t>(random() & 0xFF);
        } else {
          value = static_cast<std::uint8_t>(c == 3 ? 255 : 60 + c);
        }
        image.pixels[(static_cast<std::size_t>(y) * width + x) * channels + c] = value;
      }
    }
  }
  return image;
}

Bytes encode(const lgh::Image8& image, int level, lgh::TaskPool* pool, DeflateMode mode,
             int strips = 0) {
  const lgh::Image8View view{image.width, image.height, image.channels, image.pixels.data()};
  return lgh::image_io::detail::writePng(view, {{"Software", "test"}}, {level, pool, mode, strips});
}

// libpng's simplified reader, straight from memory.
Bytes decodeWithLibpng(const Bytes& png, int channels) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  EXPECT_TRUE(png_image_begin_read_from_memory(&image, png.data(), png.size())) << image.message;
  image.format = channels == 4 ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
  Bytes pixels(PNG_IMAGE_SIZE(image));
  EXPECT_TRUE(png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) << image.message;
  return pixels;
}

// The IDAT chunks joined, inflated whole by zlib: checks the stream's structure and Adler-32.
std::size_t inflatedSize(const Bytes& png) {
  Bytes stream;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t length =
        (png[at] << 24) | (png[at + 1] << 16) | (png[at + 2] << 8) | png[at + 3];
    if (std::memcmp(&png[at + 4], "IDAT", 4) == 0) {
      stream.insert(stream.end(), png.begin() + static_cast<std::ptrdiff_t>(at + 8),
                    png.begin() + static_cast<std::ptrdiff_t>(at + 8 + length));
    }
    at += 12 + length;
  }
  Bytes out(64 << 20);
  uLongf size = out.size();
  EXPECT_EQ(uncompress(out.data(), &size, stream.data(), stream.size()), Z_OK);
  return size;
}

void expectDecodesEverywhere(const lgh::Image8& image, const Bytes& png, const std::string& what) {
  EXPECT_EQ(decodeWithLibpng(png, image.channels), image.pixels) << what << ": libpng";
  const lgh::image_io::Decoded decoded = lgh::image_io::decode(png, what);
  EXPECT_EQ(decoded.width, image.width) << what;
  EXPECT_EQ(decoded.channels, image.channels) << what;
  EXPECT_EQ(decoded.pixels8, image.pixels) << what << ": " << lgh::image_io::backendName();
  EXPECT_EQ(inflatedSize(png),
            static_cast<std::size_t>(image.height) * (image.width * image.channels + 1))
      << what << ": zlib";
}

TEST(PngWriter, StripsJoinedWithFullFlushesDecodeIdenticallyEverywhere) {
  lgh::TaskPool pool(3);
  for (const int channels : {3, 4}) {
    const lgh::Image8 image = testImage(333, 250, channels);
    for (const int level : {1, 6, 9}) {
      for (const int strips : {1, 2, 7, 15}) {
        expectDecodesEverywhere(
            image, encode(image, level, &pool, DeflateMode::Strips, strips),
            "strips " + std::to_string(strips) + " level " + std::to_string(level));
      }
    }
    // Strips without a pool run one after another: the same bytes.
    EXPECT_EQ(encode(image, 6, nullptr, DeflateMode::Strips, 7),
              encode(image, 6, &pool, DeflateMode::Strips, 7));
  }
}

TEST(PngWriter, WholeImagesDecodeIdenticallyAtEveryLevel) {
  lgh::TaskPool pool(2);
  const lgh::Image8 image = testImage(200, 150, 3);
  std::size_t previous = 0;
  for (int level = 0; level <= 9; ++level) {
    const Bytes png = encode(image, level, &pool, DeflateMode::Whole);
    expectDecodesEverywhere(image, png, "whole level " + std::to_string(level));
    if (level == 0) EXPECT_GT(png.size(), image.pixels.size()) << "level 0 stores the rows";
    if (level == 1) EXPECT_LT(png.size(), previous) << "level 1 compresses";
    previous = png.size();
  }
}

TEST(PngWriter, TinyImagesAndSingleRows) {
  for (const auto& [width, height] : {std::pair{1, 1}, std::pair{1, 40}, std::pair{97, 1}}) {
    const lgh::Image8 image = testImage(width, height, 4);
    expectDecodesEverywhere(image, encode(image, 6, nullptr, DeflateMode::Whole), "whole tiny");
    expectDecodesEverywhere(image, encode(image, 6, nullptr, DeflateMode::Strips, 4),
                            "strips tiny");
  }
}

TEST(PngWriter, AutoPrefersStripsOnlyForLargeImagesWithManyThreads) {
  const lgh::Image8 large = testImage(1280, 720, 3);
  const lgh::Image8 thumbnail = testImage(256, 256, 3);
  const auto view = [](const lgh::Image8& image) {
    return lgh::Image8View{image.width, image.height, image.channels, image.pixels.data()};
  };
  EXPECT_TRUE(lgh::image_io::detail::prefersStrips(view(large), 6, 16));
  EXPECT_FALSE(lgh::image_io::detail::prefersStrips(view(large), 6, 2));
  EXPECT_FALSE(lgh::image_io::detail::prefersStrips(view(large), 0, 16)) << "level 0 stores";
  EXPECT_FALSE(lgh::image_io::detail::prefersStrips(view(thumbnail), 6, 16));
}

TEST(PngWriter, TextChunksRoundTrip) {
  const lgh::Image8 image = testImage(16, 8, 3);
  const Bytes png = lgh::image_io::encodePng(image, {{"Software", "lghd"}, {"lgh:x", "y z"}}, 6);
  const lgh::image_io::Decoded decoded = lgh::image_io::decode(png, "text");
  int found = 0;
  for (const auto& [key, value] : decoded.metadata) {
    if (key == "Software" && value == "lghd") ++found;
    if (key == "lgh:x" && value == "y z") ++found;
  }
  EXPECT_EQ(found, 2);
}

TEST(TaskPool, ParallelForRunsEveryIndexOnceAndRethrows) {
  lgh::TaskPool pool(3);
  std::vector<std::atomic<int>> seen(1000);
  pool.parallelFor(seen.size(), [&](std::size_t i) { seen[i].fetch_add(1); });
  for (const auto& count : seen) EXPECT_EQ(count.load(), 1);
  // Nested: a task's own parallelFor never waits on itself.
  std::atomic<int> inner{0};
  pool.parallelFor(
      8, [&](std::size_t) { pool.parallelFor(8, [&](std::size_t) { inner.fetch_add(1); }); });
  EXPECT_EQ(inner.load(), 64);
  EXPECT_THROW(pool.parallelFor(10,
                                [](std::size_t i) {
                                  if (i == 7) throw std::runtime_error("seven");
                                }),
               std::runtime_error);
  pool.waitIdle();
}

}  // namespace
