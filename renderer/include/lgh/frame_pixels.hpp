// A frame's pixels as the GPU wrote them: what the encoder stores, nothing to convert on the CPU.
//   Rgb8, Rgba8          display-encoded 8-bit (exposure, tone map, sRGB): a PNG's pixels
//   RgbaHalf, RgbaFloat  linear light, 16- or 32-bit float: an EXR's pixels
// Rows run top to bottom, tightly packed. The bytes usually live in the renderer's read-back
// memory (a mapped pixel-pack buffer, never copied); they go back to the renderer when the last
// FramePixels sharing them is destroyed or reset, from any thread (docs/ARCHITECTURE.md,
// "Frames in flight").
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "lgh/image.hpp"

namespace lgh {

// Where a frame's bytes are: read-back memory of a renderer, or a plain vector.
class PixelBytes {
 public:
  virtual ~PixelBytes() = default;
  virtual const std::uint8_t* data() const = 0;
  virtual std::size_t size() const = 0;
};

// Bytes owned by a vector (CPU-made frames, tests).
class VectorPixelBytes final : public PixelBytes {
 public:
  explicit VectorPixelBytes(std::vector<std::uint8_t> bytes) : bytes_(std::move(bytes)) {}
  const std::uint8_t* data() const override { return bytes_.data(); }
  std::size_t size() const override { return bytes_.size(); }

 private:
  std::vector<std::uint8_t> bytes_;
};

struct FramePixels {
  enum class Layout { Rgb8, Rgba8, RgbaHalf, RgbaFloat };

  int width = 0;
  int height = 0;
  Layout layout = Layout::Rgba8;
  std::shared_ptr<const PixelBytes> bytes;  // null once released

  bool empty() const { return bytes == nullptr; }
  const std::uint8_t* data() const { return bytes ? bytes->data() : nullptr; }
  std::size_t size() const;  // width * height * bytesPerPixel()
  int channels() const { return layout == Layout::Rgb8 ? 3 : 4; }
  std::size_t bytesPerPixel() const;
  bool isDisplay() const { return layout == Layout::Rgb8 || layout == Layout::Rgba8; }

  // Copies for callers that want the older image types (tests, tools). Throws lgh::Error
  // (Internal) when the layout does not fit: a display frame has no linear values, and a linear
  // frame no display bytes.
  FloatImage toFloatImage() const;
  Image8 toImage8() const;

  // Gives the bytes back (to the renderer's read-back memory) before this object goes.
  void release() { bytes.reset(); }
};

// The layout a frame of `output` is read back in: PNG -> Rgb8 (Rgba8 with a transparent
// background), EXR half -> RgbaHalf, EXR float -> RgbaFloat.
FramePixels::Layout pixelLayoutFor(const OutputSettings& output);

// Encodes the pixels in `output`'s format, which must be the one they were read back for (a PNG
// from display bytes, an EXR from linear halves or floats): nothing is converted on the way. Any
// thread. With a pool, a large PNG is filtered and deflated on its idle workers too.
std::vector<std::uint8_t> encodeFrame(const FramePixels& pixels, const OutputSettings& output,
                                      const ImageMetadata& metadata, TaskPool* pool = nullptr);

// A half float (IEEE 754 binary16) widened to float, exactly.
float halfToFloat(std::uint16_t half);

}  // namespace lgh
