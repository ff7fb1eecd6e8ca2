#include "lgh/frame_pixels.hpp"

#include <bit>
#include <cstring>

#include <fmt/format.h>

#include "lgh/error.hpp"

namespace lgh {

std::size_t FramePixels::bytesPerPixel() const {
  switch (layout) {
    case Layout::Rgb8:
      return 3;
    case Layout::Rgba8:
      return 4;
    case Layout::RgbaHalf:
      return 8;
    case Layout::RgbaFloat:
      return 16;
  }
  return 4;
}

std::size_t FramePixels::size() const {
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * bytesPerPixel();
}

namespace {

void checkHeld(const FramePixels& pixels) {
  if (pixels.empty() || pixels.bytes->size() < pixels.size()) {
    throw Error(ErrorCode::Internal, fmt::format("frame pixels of {}x{} are released or short",
                                                 pixels.width, pixels.height));
  }
}

}  // namespace

float halfToFloat(std::uint16_t half) {
  const std::uint32_t sign = static_cast<std::uint32_t>(half & 0x8000U) << 16;
  std::uint32_t exponent = (half >> 10) & 0x1FU;
  std::uint32_t mantissa = half & 0x3FFU;
  if (exponent == 0x1F) return std::bit_cast<float>(sign | 0x7F800000U | (mantissa << 13));
  if (exponent == 0) {
    if (mantissa == 0) return std::bit_cast<float>(sign);
    // A subnormal half is a normal float: shift the mantissa up to its leading one.
    exponent = 113;  // 127 - 15 + 1
    while ((mantissa & 0x400U) == 0) {
      mantissa <<= 1;
      --exponent;
    }
    mantissa &= 0x3FFU;
    return std::bit_cast<float>(sign | (exponent << 23) | (mantissa << 13));
  }
  return std::bit_cast<float>(sign | ((exponent + 112) << 23) | (mantissa << 13));
}

FloatImage FramePixels::toFloatImage() const {
  checkHeld(*this);
  if (isDisplay()) {
    throw Error(ErrorCode::Internal,
                "a display-encoded (PNG) frame has no linear values: render as exr-float");
  }
  FloatImage image;
  image.width = width;
  image.height = height;
  image.rgba.resize(static_cast<std::size_t>(width) * height * 4);
  if (layout == Layout::RgbaFloat) {
    std::memcpy(image.rgba.data(), data(), image.rgba.size() * sizeof(float));
    return image;
  }
  const std::uint8_t* halves = data();
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    std::uint16_t half = 0;
    std::memcpy(&half, halves + 2 * i, sizeof half);
    image.rgba[i] = halfToFloat(half);
  }
  return image;
}

Image8 FramePixels::toImage8() const {
  checkHeld(*this);
  if (!isDisplay()) {
    throw Error(ErrorCode::Internal, "a linear (EXR) frame has no display bytes: render as png");
  }
  return Image8{width, height, channels(), std::vector<std::uint8_t>(data(), data() + size())};
}

FramePixels::Layout pixelLayoutFor(const OutputSettings& output) {
  switch (output.format) {
    case ImageFormat::Png:
      return output.transparentBackground ? FramePixels::Layout::Rgba8 : FramePixels::Layout::Rgb8;
    case ImageFormat::ExrHalf:
      return FramePixels::Layout::RgbaHalf;
    case ImageFormat::ExrFloat:
      return FramePixels::Layout::RgbaFloat;
  }
  return FramePixels::Layout::Rgba8;
}

std::vector<std::uint8_t> encodeFrame(const FramePixels& pixels, const OutputSettings& output,
                                      const ImageMetadata& metadata, TaskPool* pool) {
  checkHeld(pixels);
  if (pixels.layout != pixelLayoutFor(output)) {
    throw Error(ErrorCode::Internal,
                "the frame was read back for another output format than the one asked to encode");
  }
  switch (output.format) {
    case ImageFormat::Png:
      return image_io::encodePng(
          Image8View{pixels.width, pixels.height, pixels.channels(), pixels.data()}, metadata,
          output.pngCompression, pool);
    case ImageFormat::ExrHalf:
    case ImageFormat::ExrFloat: {
      const bool half = output.format == ImageFormat::ExrHalf;
      return image_io::encodeExr(
          LinearRgbaView{pixels.width, pixels.height,
                         pixels.layout == FramePixels::Layout::RgbaHalf, pixels.data()},
          half, metadata);
    }
  }
  throw Error(ErrorCode::Internal, "unknown output image format");
}

}  // namespace lgh
