// Image I/O on libpng (PNG, read), OpenEXR 3.1 (EXR) and libjpeg-turbo (JPEG, read only): small
// enough to ship with the GPU bundle. PNG files are written by the shared encoder (png_writer.hpp).
// (JPEG went through stb_image until fuzzing found undefined behaviour in its Huffman table code;
// stb_image is not meant for untrusted input, libjpeg-turbo is fuzzed continuously upstream, and
// OpenImageIO uses it too.) Everything happens in memory: libpng through a read callback, OpenEXR
// through IStream/OStream subclasses over byte buffers.
#include <climits>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include <Imath/half.h>
#include <OpenEXR/IexBaseExc.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <fmt/format.h>
#include <png.h>

#include "image/image_common.hpp"
#include "lgh/error.hpp"
#include "lgh/image.hpp"

// After <cstdio>: jpeglib.h needs FILE and size_t declared before it.
#include <jpeglib.h>

namespace lgh::image_io {

namespace {

using detail::FileKind;
using detail::MetadataFormat;

// ---- libpng plumbing ----
//
// libpng reports errors through a callback that must not return: it longjmps back to the setjmp
// in one of the *Guarded functions below. C++ only allows that when the jump skips no destructor,
// so those functions create no objects with destructors; everything they fill belongs to their
// caller, and every allocation happens outside them.

struct PngIo {
  const std::uint8_t* input = nullptr;  // reading
  std::size_t inputSize = 0;
  std::size_t position = 0;
  char error[256] = {};
};

void onPngError(png_structp png, png_const_charp message) {
  auto* io = static_cast<PngIo*>(png_get_error_ptr(png));
  std::snprintf(io->error, sizeof io->error, "%s", message);
  png_longjmp(png, 1);
}

// Warnings are about damaged ancillary chunks, which libpng skips; the image is still good.
void onPngWarning(png_structp /*png*/, png_const_charp /*message*/) {}

void readFromMemory(png_structp png, png_bytep destination, std::size_t length) {
  auto* io = static_cast<PngIo*>(png_get_io_ptr(png));
  if (length > io->inputSize - io->position) png_error(png, "unexpected end of PNG data");
  std::memcpy(destination, io->input + io->position, length);
  io->position += length;
}

// Owns a png_struct and its png_info for reading.
class PngStructs {
 public:
  explicit PngStructs(PngIo& io) {
    png_ = png_create_read_struct(PNG_LIBPNG_VER_STRING, &io, onPngError, onPngWarning);
    if (png_) info_ = png_create_info_struct(png_);
    if (!png_ || !info_) {
      destroy();
      throw Error(ErrorCode::Internal, "libpng could not allocate its structures");
    }
    png_set_read_fn(png_, &io, readFromMemory);
  }
  PngStructs(const PngStructs&) = delete;
  PngStructs& operator=(const PngStructs&) = delete;
  ~PngStructs() { destroy(); }

  png_structp png() const { return png_; }
  png_infop info() const { return info_; }

 private:
  void destroy() { png_destroy_read_struct(&png_, info_ ? &info_ : nullptr, nullptr); }

  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
};

// ---- PNG decoding ----

struct PngLayout {
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int channels = 0;
  std::size_t rowBytes = 0;
};

// Reads the header and sets up 8-bit output: palette and low bit depths expanded, tRNS to alpha,
// 16 bits scaled with rounding (the conversion OpenImageIO does), and with `rgba` grey widened to
// RGB and an opaque alpha added where there is none.
bool readPngHeaderGuarded(png_structp png, png_infop info, bool rgba, PngLayout& layout) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  png_set_expand(png);
  png_set_scale_16(png);
  png_set_interlace_handling(png);
  if (rgba) {
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER);
  }
  png_read_update_info(png, info);
  layout.width = png_get_image_width(png, info);
  layout.height = png_get_image_height(png, info);
  layout.channels = png_get_channels(png, info);
  layout.rowBytes = png_get_rowbytes(png, info);
  return true;
}

bool readPngRowsGuarded(png_structp png, png_infop info, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, info);  // text chunks after the image data land in `info` too
  return true;
}

Error brokenImage(const char* format, const char* reason, const std::string& what) {
  return Error(ErrorCode::Invalid,
               fmt::format("broken {} image: {}", format, detail::printable(reason)), what);
}

struct Pixels8 {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<std::uint8_t> pixels;
  ImageMetadata metadata;
};

ImageMetadata pngText(png_structp png, png_infop info) {
  png_textp text = nullptr;
  int count = 0;
  png_get_text(png, info, &text, &count);
  ImageMetadata metadata;
  for (int i = 0; i < count; ++i) {
    // NUL-terminated; text_length is 0 for iTXt chunks, whose length is in itxt_length.
    metadata.emplace_back(text[i].key, text[i].text != nullptr ? text[i].text : "");
  }
  return metadata;
}

Pixels8 readPng(const std::uint8_t* data, std::size_t size, bool rgba, const std::string& what) {
  detail::checkPngChunks(data, size, what);  // as the OIIO backend does, for the same errors
  PngIo io;
  io.input = data;
  io.inputSize = size;
  PngStructs structs(io);
  PngLayout layout;
  if (!readPngHeaderGuarded(structs.png(), structs.info(), rgba, layout)) {
    throw brokenImage("PNG", io.error, what);
  }
  detail::checkDecodeSize(layout.width, layout.height, what);
  if (layout.rowBytes != static_cast<std::size_t>(layout.width) * layout.channels ||
      (rgba && layout.channels != 4)) {
    throw brokenImage("PNG", "unexpected pixel layout after conversion to 8 bits", what);
  }
  Pixels8 result{
      static_cast<int>(layout.width), static_cast<int>(layout.height), layout.channels, {}, {}};
  result.pixels.resize(layout.rowBytes * layout.height);
  std::vector<png_bytep> rows(layout.height);
  for (png_uint_32 y = 0; y < layout.height; ++y) rows[y] = &result.pixels[y * layout.rowBytes];
  if (!readPngRowsGuarded(structs.png(), structs.info(), rows.data())) {
    throw brokenImage("PNG", io.error, what);
  }
  result.metadata = pngText(structs.png(), structs.info());
  return result;
}

// ---- JPEG decoding (libjpeg-turbo) ----
//
// libjpeg reports errors through error_exit, which must not return: it longjmps back to the
// setjmp in one of the *Guarded functions below, which, as for libpng, create no objects with
// destructors.

// Progressive JPEGs may hold any number of scans, each a pass over the whole image: a small file
// with thousands of them costs minutes (libjpeg-turbo's own fuzzers stop at 500).
constexpr int kMaxJpegScans = 500;

struct JpegError {
  jpeg_error_mgr manager;  // first: libjpeg hands back a pointer to it
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void jpegErrorExit(j_common_ptr info) {
  auto* error = reinterpret_cast<JpegError*>(info->err);
  (*info->err->format_message)(info, error->message);
  std::longjmp(error->jump, 1);
}

// Warnings (corrupt data that libjpeg can decode around) are not errors, as in OpenImageIO.
void jpegIgnoreMessage(j_common_ptr /*info*/, int /*level*/) {}

void jpegCountScans(j_common_ptr info) {
  const auto* decompress = reinterpret_cast<j_decompress_ptr>(info);
  if (decompress->input_scan_number > kMaxJpegScans) {
    auto* error = reinterpret_cast<JpegError*>(info->err);
    std::snprintf(error->message, sizeof(error->message), "more than %d progressive scans",
                  kMaxJpegScans);
    std::longjmp(error->jump, 1);
  }
}

// A decompressor and its error manager, created and destroyed together.
class JpegDecoder {
 public:
  JpegDecoder() {
    info_.err = jpeg_std_error(&error_.manager);
    error_.manager.error_exit = &jpegErrorExit;
    error_.manager.emit_message = &jpegIgnoreMessage;
    progress_.progress_monitor = &jpegCountScans;
    created_ = createGuarded();
  }
  ~JpegDecoder() {
    if (created_) jpeg_destroy_decompress(&info_);
  }
  JpegDecoder(const JpegDecoder&) = delete;
  JpegDecoder& operator=(const JpegDecoder&) = delete;

  bool created() const { return created_; }
  jpeg_decompress_struct& info() { return info_; }
  const char* message() const { return error_.message; }

  bool readHeaderGuarded(const std::uint8_t* data, std::size_t size) {
    if (setjmp(error_.jump)) return false;
    jpeg_mem_src(&info_, data, static_cast<unsigned long>(size));
    jpeg_read_header(&info_, TRUE);
    info_.progress = &progress_;
    return true;
  }

  bool startGuarded() {
    if (setjmp(error_.jump)) return false;
    jpeg_start_decompress(&info_);
    return true;
  }

  bool readRowsGuarded(std::uint8_t* pixels, std::size_t rowBytes) {
    if (setjmp(error_.jump)) return false;
    while (info_.output_scanline < info_.output_height) {
      JSAMPROW row = pixels + static_cast<std::size_t>(info_.output_scanline) * rowBytes;
      jpeg_read_scanlines(&info_, &row, 1);
    }
    jpeg_finish_decompress(&info_);
    return true;
  }

 private:
  bool createGuarded() {
    error_.message[0] = 0;
    if (setjmp(error_.jump)) return false;
    jpeg_create_decompress(&info_);
    return true;
  }

  jpeg_decompress_struct info_{};
  JpegError error_{};
  jpeg_progress_mgr progress_{};
  bool created_ = false;
};

// Adobe CMYK and YCCK JPEGs store inverted ink: R = C * K / 255 (as in OpenImageIO and
// stb_image).
void cmykToRgb(const std::vector<std::uint8_t>& cmyk, std::size_t pixels, int channels,
               std::vector<std::uint8_t>& out) {
  out.resize(pixels * static_cast<std::size_t>(channels));
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::uint8_t* ink = &cmyk[i * 4];
    for (int c = 0; c < 3; ++c) {
      out[i * channels + c] = static_cast<std::uint8_t>((ink[c] * ink[3] + 127) / 255);
    }
    if (channels == 4) out[i * channels + 3] = 0xFF;
  }
}

// `desiredChannels` 0 keeps the file's channels (1, or 3 for colour); 4 gives RGBA.
Pixels8 readJpeg(const std::uint8_t* data, std::size_t size, int desiredChannels,
                 const std::string& what) {
  if (size > static_cast<std::size_t>(INT_MAX)) {
    throw Error(ErrorCode::TooLarge, "JPEG data over 2 GiB", what);
  }
  JpegDecoder decoder;
  if (!decoder.created()) throw brokenImage("JPEG", decoder.message(), what);
  if (!decoder.readHeaderGuarded(data, size)) throw brokenImage("JPEG", decoder.message(), what);
  jpeg_decompress_struct& info = decoder.info();
  detail::checkDecodeSize(info.image_width, info.image_height, what);
  const bool ink = info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK;
  const bool grey = info.jpeg_color_space == JCS_GRAYSCALE;
  const int channels = desiredChannels != 0 ? desiredChannels : (grey ? 1 : 3);
  if (ink) {
    info.out_color_space = JCS_CMYK;
  } else if (channels == 4) {
    info.out_color_space = JCS_EXT_RGBA;
  } else {
    info.out_color_space = channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
  }
  if (!decoder.startGuarded()) throw brokenImage("JPEG", decoder.message(), what);
  const int outputChannels = info.output_components;
  const std::size_t width = info.output_width;
  const std::size_t height = info.output_height;
  std::vector<std::uint8_t> decoded(width * height * static_cast<std::size_t>(outputChannels));
  if (!decoder.readRowsGuarded(decoded.data(), width * static_cast<std::size_t>(outputChannels))) {
    throw brokenImage("JPEG", decoder.message(), what);
  }
  Pixels8 result{static_cast<int>(width), static_cast<int>(height), channels, {}, {}};
  if (ink) {
    cmykToRgb(decoded, width * height, channels == 1 ? 3 : channels, result.pixels);
    if (channels == 1) result.channels = 3;
  } else {
    result.pixels = std::move(decoded);
  }
  return result;
}

// ---- OpenEXR streams over memory ----

class VectorOStream final : public Imf::OStream {
 public:
  explicit VectorOStream(std::vector<std::uint8_t>& bytes)
      : Imf::OStream("memory"), bytes_(bytes) {}

  void write(const char c[], int n) override {
    const std::size_t end = position_ + static_cast<std::size_t>(n);
    if (end > bytes_.size()) bytes_.resize(end);
    std::memcpy(bytes_.data() + position_, c, static_cast<std::size_t>(n));
    position_ = end;
  }
  std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t position) override { position_ = position; }

 private:
  std::vector<std::uint8_t>& bytes_;
  std::size_t position_ = 0;
};

class MemoryIStream final : public Imf::IStream {
 public:
  MemoryIStream(const std::uint8_t* data, std::size_t size)
      : Imf::IStream("memory"), data_(data), size_(size) {}

  bool read(char c[], int n) override {
    if (n < 0 || position_ > size_ || static_cast<std::size_t>(n) > size_ - position_) {
      throw Iex::InputExc("unexpected end of OpenEXR data");
    }
    std::memcpy(c, data_ + position_, static_cast<std::size_t>(n));
    position_ += static_cast<std::size_t>(n);
    return position_ < size_;
  }
  std::uint64_t tellg() override { return position_; }
  void seekg(std::uint64_t position) override { position_ = position; }
  void clear() override {}

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

constexpr const char* kRgbaChannels[] = {"R", "G", "B", "A"};

// ---- OpenEXR encoding ----

// The pixels as the file stores them: OpenEXR's scanline writer converts between frame buffer and
// file pixel types only on read, so a half file from floats needs a half buffer (Imath's
// conversion rounds to nearest even, as OpenImageIO's does). Half pixels are stored as they are.
struct ExrPixels {
  Imf::PixelType type;
  std::vector<Imath::half> halves;
  const void* data;
  std::size_t valueSize;
};

ExrPixels filePixels(const LinearRgbaView& image, bool halfFloat) {
  if (image.halfFloat) return {Imf::HALF, {}, image.pixels, sizeof(Imath::half)};
  if (!halfFloat) return {Imf::FLOAT, {}, image.pixels, sizeof(float)};
  const auto* floats = static_cast<const float*>(image.pixels);
  const std::size_t count = static_cast<std::size_t>(image.width) * image.height * 4;
  ExrPixels pixels{Imf::HALF, std::vector<Imath::half>(floats, floats + count), nullptr,
                   sizeof(Imath::half)};
  pixels.data = pixels.halves.data();
  return pixels;
}

void writeExr(const LinearRgbaView& image, bool halfFloat, const ImageMetadata& metadata,
              std::vector<std::uint8_t>& bytes) {
  const ExrPixels pixels = filePixels(image, halfFloat);
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const char* name : kRgbaChannels) header.channels().insert(name, Imf::Channel(pixels.type));
  for (const auto& [key, value] : metadata) header.insert(key, Imf::StringAttribute(value));

  Imf::FrameBuffer frame;
  const std::size_t xStride = 4 * pixels.valueSize;
  const std::size_t yStride = xStride * static_cast<std::size_t>(image.width);
  for (int c = 0; c < 4; ++c) {
    const auto* base = static_cast<const char*>(pixels.data) + c * pixels.valueSize;
    frame.insert(kRgbaChannels[c], Imf::Slice::Make(pixels.type, base, Imath::V2i(0, 0),
                                                    image.width, image.height, xStride, yStride));
  }
  VectorOStream stream(bytes);
  Imf::OutputFile file(stream, header);  // its destructor writes the line offset table
  file.setFrameBuffer(frame);
  file.writePixels(image.height);
}

// ---- OpenEXR decoding ----

// RGB, plus A when the file has it; a missing R, G or B reads as 0.
Decoded readExrUnchecked(const std::uint8_t* data, std::size_t size, const std::string& what) {
  detail::checkExrHeader(data, size, what);
  MemoryIStream stream(data, size);
  Imf::InputFile file(stream);
  const Imath::Box2i window = file.header().dataWindow();
  const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
  const std::int64_t height = std::int64_t{window.max.y} - window.min.y + 1;
  detail::checkDecodeSize(width, height, what);

  Decoded decoded;
  decoded.width = static_cast<int>(width);
  decoded.height = static_cast<int>(height);
  decoded.channels = file.header().channels().findChannel("A") ? 4 : 3;
  decoded.isFloat = true;
  decoded.pixelsFloat.resize(static_cast<std::size_t>(width * height) * decoded.channels);

  Imf::FrameBuffer frame;
  const std::size_t xStride = sizeof(float) * decoded.channels;
  const std::size_t yStride = xStride * static_cast<std::size_t>(width);
  for (int c = 0; c < decoded.channels; ++c) {
    frame.insert(kRgbaChannels[c], Imf::Slice::Make(Imf::FLOAT, decoded.pixelsFloat.data() + c,
                                                    window, xStride, yStride));
  }
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);

  for (auto it = file.header().begin(); it != file.header().end(); ++it) {
    if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) {
      decoded.metadata.emplace_back(it.name(), text->value());
    }
  }
  return decoded;
}

Decoded readExr(const std::uint8_t* data, std::size_t size, const std::string& what) {
  try {
    return readExrUnchecked(data, size, what);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // Iex::BaseExc and std::bad_alloc
    throw brokenImage("OpenEXR", e.what(), what);
  }
}

Decoded toDecoded(Pixels8&& image) {
  Decoded decoded;
  decoded.width = image.width;
  decoded.height = image.height;
  decoded.channels = image.channels;
  decoded.pixels8 = std::move(image.pixels);
  decoded.metadata = std::move(image.metadata);
  return decoded;
}

}  // namespace

const char* backendName() { return "lean"; }

std::vector<std::uint8_t> encodeExr(const LinearRgbaView& image, bool halfFloat,
                                    const ImageMetadata& metadata) {
  detail::checkLinearRgbaView(image, halfFloat);
  detail::checkMetadata(metadata, MetadataFormat::Exr);
  std::vector<std::uint8_t> bytes;
  try {
    writeExr(image, halfFloat, detail::withCaptureDate(metadata), bytes);
  } catch (const std::exception& e) {
    throw Error(ErrorCode::Internal, fmt::format("OpenEXR could not encode: {}", e.what()));
  }
  return bytes;
}

Decoded decode(const std::vector<std::uint8_t>& bytes, const std::string& what) {
  if (bytes.empty()) throw Error(ErrorCode::Invalid, "empty image data", what);
  switch (detail::sniffFileKind(bytes.data(), bytes.size())) {
    case FileKind::Png:
      return toDecoded(readPng(bytes.data(), bytes.size(), false, what));
    case FileKind::Exr:
      return readExr(bytes.data(), bytes.size(), what);
    case FileKind::Jpeg:
      return toDecoded(readJpeg(bytes.data(), bytes.size(), 0, what));
    case FileKind::Unknown:
      break;
  }
  throw Error(ErrorCode::Invalid,
              "not a PNG, JPEG or OpenEXR image (the formats of the lean image backend)", what);
}

Image8 decodeTextureRgba8(const std::uint8_t* data, std::size_t size, const std::string& what) {
  if (size == 0) throw Error(ErrorCode::Invalid, "empty image data", what);
  Pixels8 image;
  switch (detail::sniffFileKind(data, size)) {
    case FileKind::Png:
      image = readPng(data, size, true, what);
      break;
    case FileKind::Jpeg:
      image = readJpeg(data, size, 4, what);
      break;
    default:
      throw Error(ErrorCode::Invalid, "texture is not a PNG or JPEG image", what);
  }
  return Image8{image.width, image.height, 4, std::move(image.pixels)};
}

}  // namespace lgh::image_io
