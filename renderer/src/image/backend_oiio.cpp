// Image I/O on OpenImageIO 2.4: every format it reads, all in memory through its IOProxy classes
// (IOVecOutput to encode, IOMemReader to decode), so no temporary files.
#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>
#include <fmt/format.h>

#include "image/image_common.hpp"
#include "lgh/error.hpp"
#include "lgh/image.hpp"

namespace lgh::image_io {

namespace {

using detail::FileKind;
using detail::MetadataFormat;

// OpenImageIO reads some metadata keys back under its own names; map them back to the key that
// is in the file (and that the lean backend returns). Keys that would be ambiguous are reserved
// (detail::isReservedMetadataKey), so these maps are one to one.
struct KeyAlias {
  std::string_view fileKey;
  std::string_view oiioName;
};
constexpr KeyAlias kPngReadAliases[] = {
    {"Description", "ImageDescription"}, {"Author", "Artist"}, {"Title", "DocumentName"}};
constexpr KeyAlias kExrReadAliases[] = {
    {"comments", "ImageDescription"}, {"owner", "Copyright"}, {"capDate", "DateTime"}};
// The EXR writer drops a plain "capDate" string and writes "DateTime" as capDate instead.
constexpr KeyAlias kExrWriteAliases[] = {{"capDate", "DateTime"}};

template <std::size_t N>
std::string_view oiioNameFor(std::string_view fileKey, const KeyAlias (&aliases)[N]) {
  for (const auto& alias : aliases) {
    if (alias.fileKey == fileKey) return alias.oiioName;
  }
  return fileKey;
}

template <std::size_t N>
std::string_view fileKeyFor(std::string_view oiioName, const KeyAlias (&aliases)[N]) {
  for (const auto& alias : aliases) {
    if (alias.oiioName == oiioName) return alias.fileKey;
  }
  return oiioName;
}

// ---- Encoding ----

// Runs one ImageOutput into memory. `virtualName` only tells OpenImageIO the format.
std::vector<std::uint8_t> writeToMemory(const char* virtualName, OIIO::ImageSpec spec,
                                        const OIIO::TypeDesc& dataType, const void* data) {
  std::vector<std::uint8_t> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  OIIO::Filesystem::IOProxy* proxyPointer = &proxy;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxyPointer);
  auto output = OIIO::ImageOutput::create(virtualName);
  if (!output) {
    throw Error(ErrorCode::Internal,
                fmt::format("OpenImageIO has no writer for {}: {}", virtualName, OIIO::geterror()));
  }
  if (!output->open(virtualName, spec) || !output->write_image(dataType, data) ||
      !output->close()) {
    throw Error(ErrorCode::Internal, fmt::format("OpenImageIO could not encode {}: {}", virtualName,
                                                 output->geterror()));
  }
  output.reset();  // done with `proxy` before `bytes` leaves
  return bytes;
}

// ---- Decoding ----

// The proxy must outlive the input that reads through it: members are destroyed bottom up.
struct OpenInput {
  std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy;
  std::unique_ptr<OIIO::ImageInput> input;
  std::string format;  // OpenImageIO's format name, e.g. "png"
};

// OpenImageIO's plugin for the bytes' magic number; empty when unrecognised.
std::string sniffFormat(const std::uint8_t* data, std::size_t size) {
  switch (detail::sniffFileKind(data, size)) {
    case FileKind::Png:
      return "png";
    case FileKind::Exr:
      return "openexr";
    case FileKind::Jpeg:
      return "jpeg";
    case FileKind::Unknown:
      break;
  }
  auto startsWith = [&](std::string_view magic) {
    return size >= magic.size() && std::memcmp(data, magic.data(), magic.size()) == 0;
  };
  if (startsWith("II*") || startsWith(std::string_view("MM\0*", 4))) return "tiff";
  if (startsWith("GIF8")) return "gif";
  if (startsWith("BM")) return "bmp";
  if (startsWith("#?")) return "hdr";
  if (startsWith("8BPS")) return "psd";
  if (startsWith("DDS ")) return "dds";
  if (size >= 12 && startsWith("RIFF") && std::memcmp(data + 8, "WEBP", 4) == 0) return "webp";
  return {};
}

// Opens the bytes with one named plugin; null when it cannot (its error is in `error`). The
// plugin is created by name, without the proxy: given a proxy, ImageInput::create() tries every
// plugin in turn when the first fails, which takes seconds on a damaged file.
std::unique_ptr<OIIO::ImageInput> tryOpen(const std::string& format,
                                          OIIO::Filesystem::IOMemReader& proxy,
                                          std::string& error) {
  auto input = OIIO::ImageInput::create(format);
  if (!input || !input->supports("ioproxy")) {
    // Without proxy support the plugin would open a file named like our virtual name.
    error = fmt::format("OpenImageIO cannot read {} from memory", format);
    (void)OIIO::geterror();  // clear the thread's pending error
    return nullptr;
  }
  OIIO::ImageSpec config;
  OIIO::Filesystem::IOProxy* proxyPointer = &proxy;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxyPointer);
  // PNG stores unassociated alpha; keep it as stored instead of premultiplying.
  config.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::ImageSpec spec;
  if (!input->open("memory", spec, config)) {
    error = input->geterror();
    return nullptr;
  }
  return input;
}

// Formats without a recognised magic number: ask every plugin that can read from memory.
OpenInput openByProbing(const std::uint8_t* data, std::size_t size, const std::string& what) {
  std::string formats;
  OIIO::getattribute("input_format_list", formats);
  for (const auto& format : OIIO::Strutil::splitsv(formats, ",")) {
    auto proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(data, size);
    std::string ignored;
    if (auto input = tryOpen(std::string(format), *proxy, ignored)) {
      return {std::move(proxy), std::move(input), std::string(format)};
    }
  }
  throw Error(ErrorCode::Invalid, "not an image in any format OpenImageIO reads", what);
}

OpenInput openFromMemory(const std::uint8_t* data, std::size_t size, const std::string& what) {
  if (size == 0) throw Error(ErrorCode::Invalid, "empty image data", what);
  const std::string format = sniffFormat(data, size);
  // Damaged sizes in these headers cost gigabytes or tens of seconds inside OpenImageIO.
  if (format == "openexr") detail::checkExrHeader(data, size, what);
  if (format == "png") detail::checkPngChunks(data, size, what);
  OpenInput opened;
  if (format.empty()) {
    opened = openByProbing(data, size, what);
  } else {
    opened.proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(data, size);
    std::string error;
    opened.input = tryOpen(format, *opened.proxy, error);
    if (!opened.input) {
      throw Error(ErrorCode::Invalid,
                  fmt::format("broken {} image: {}", format, detail::printable(error)), what);
    }
    opened.format = format;
  }
  const OIIO::ImageSpec& spec = opened.input->spec();
  detail::checkDecodeSize(spec.width, spec.height, what);
  return opened;
}

bool isFloatFormat(const OIIO::TypeDesc& format) {
  return format.basetype == OIIO::TypeDesc::HALF || format.basetype == OIIO::TypeDesc::FLOAT ||
         format.basetype == OIIO::TypeDesc::DOUBLE;
}

// Reads channels [0, channels) of the first subimage, converted to `type`.
void readPixels(OpenInput& opened, int channels, const OIIO::TypeDesc& type, void* destination,
                const std::string& what) {
  if (!opened.input->read_image(0, 0, 0, channels, type, destination)) {
    throw Error(ErrorCode::Invalid,
                fmt::format("broken {} image: {}", opened.format,
                            detail::printable(opened.input->geterror())),
                what);
  }
}

// The file's string attributes under the names they have in the file, without the attributes
// OpenImageIO synthesises (oiio:*, compression, ...).
ImageMetadata readMetadata(const OIIO::ImageSpec& spec, const std::string& format) {
  const bool isExr = format == "openexr";
  const MetadataFormat rules = isExr ? MetadataFormat::Exr : MetadataFormat::Png;
  ImageMetadata metadata;
  for (const auto& attribute : spec.extra_attribs) {
    if (attribute.type() != OIIO::TypeString) continue;
    const std::string_view oiioName = attribute.name().string();
    const std::string_view key =
        isExr ? fileKeyFor(oiioName, kExrReadAliases) : fileKeyFor(oiioName, kPngReadAliases);
    if (detail::isReservedMetadataKey(key, rules)) continue;
    metadata.emplace_back(std::string(key), attribute.get_string());
  }
  return metadata;
}

}  // namespace

const char* backendName() { return "oiio"; }

std::vector<std::uint8_t> encodeExr(const LinearRgbaView& image, bool halfFloat,
                                    const ImageMetadata& metadata) {
  detail::checkLinearRgbaView(image, halfFloat);
  detail::checkMetadata(metadata, MetadataFormat::Exr);
  OIIO::ImageSpec spec(image.width, image.height, 4,
                       halfFloat ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  for (const auto& [key, value] : detail::withCaptureDate(metadata)) {
    spec.attribute(std::string(oiioNameFor(key, kExrWriteAliases)), value);
  }
  return writeToMemory("memory.exr", spec,
                       image.halfFloat ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT,
                       image.pixels);
}

Decoded decode(const std::vector<std::uint8_t>& bytes, const std::string& what) {
  OpenInput opened = openFromMemory(bytes.data(), bytes.size(), what);
  const OIIO::ImageSpec& spec = opened.input->spec();
  Decoded decoded;
  decoded.width = spec.width;
  decoded.height = spec.height;
  decoded.channels = spec.nchannels;
  decoded.isFloat = isFloatFormat(spec.format);
  const std::size_t values = spec.image_pixels() * static_cast<std::size_t>(spec.nchannels);
  if (decoded.isFloat) {
    decoded.pixelsFloat.resize(values);
    readPixels(opened, spec.nchannels, OIIO::TypeDesc::FLOAT, decoded.pixelsFloat.data(), what);
  } else {
    decoded.pixels8.resize(values);
    readPixels(opened, spec.nchannels, OIIO::TypeDesc::UINT8, decoded.pixels8.data(), what);
  }
  decoded.metadata = readMetadata(spec, opened.format);
  return decoded;
}

Image8 decodeTextureRgba8(const std::uint8_t* data, std::size_t size, const std::string& what) {
  // glTF textures are PNG or JPEG. OpenImageIO would probe every format it has a reader for
  // (TIFF, DPX, PSD, ...), which is far more code for hostile bytes to reach; the lean backend
  // reads these two only, and so does this one.
  const FileKind kind = size == 0 ? FileKind::Unknown : detail::sniffFileKind(data, size);
  if (size > 0 && kind != FileKind::Png && kind != FileKind::Jpeg) {
    throw Error(ErrorCode::Invalid, "texture is not a PNG or JPEG image", what);
  }
  OpenInput opened = openFromMemory(data, size, what);
  const OIIO::ImageSpec& spec = opened.input->spec();
  // Grey, grey + alpha, RGB or RGBA; extra channels (e.g. depth) are not part of a texture.
  const int channels = std::min(spec.nchannels, 4);
  std::vector<std::uint8_t> pixels(spec.image_pixels() * static_cast<std::size_t>(channels));
  readPixels(opened, channels, OIIO::TypeDesc::UINT8, pixels.data(), what);
  return detail::expandToRgba8(spec.width, spec.height, channels, pixels.data());
}

}  // namespace lgh::image_io
