// Backend-independent image code: display conversion (exposure, tone map, sRGB), the request-level
// encoder, file I/O, and the input rules both backends share (image_common.hpp).
#include "image/image_common.hpp"

#include <unistd.h>
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <limits>
#include <memory>
#include <set>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "lgh/error.hpp"

namespace lgh {

namespace {

// ---- Display conversion ----

// Larger linear values all display as white; clamping first keeps Reinhard and ACES away from
// inf / inf.
constexpr float kMaxLinear = 1.0e6F;

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a fit of the ACES RRT + ODT for sRGB.
float acesFilmic(float x) { return (x * (2.51F * x + 0.03F)) / (x * (2.43F * x + 0.59F) + 0.14F); }

float toneMap(float value, ToneMap mode) {
  switch (mode) {
    case ToneMap::None:
      return value;
    case ToneMap::Reinhard:
      return value / (1.0F + value);
    case ToneMap::Aces:
      return acesFilmic(value);
  }
  return value;
}

// The inverse of the sRGB OETF, in double, to build the table below.
double srgbInverseOetf(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// threshold[k] is the smallest float linear value whose sRGB encoding rounds to code k + 1, i.e.
// the inverse OETF of (k + 0.5) / 255, rounded up to a float. Counting the thresholds at or below a
// value gives exactly round(255 * oetf(value)) without a pow() per channel.
//
// The count is found in two steps instead of a binary search per channel (which cost as much as
// the PNG encode itself; docs/BENCHMARKS.md, "Output"): a value's top bits
// (exponent and first 8 mantissa bits) index a table holding the count at the smallest float with
// those bits, and a threshold left between that float and the value is stepped over by
// comparison. A bucket spans 0.4 % of its value, less than one code's width, so the loop steps at
// most once.
class SrgbEncoder {
 public:
  SrgbEncoder() {
    for (int k = 0; k < 255; ++k) {
      const double exact = srgbInverseOetf((k + 0.5) / 255.0);
      float rounded = static_cast<float>(exact);
      if (static_cast<double>(rounded) < exact) {
        rounded = std::nextafter(rounded, std::numeric_limits<float>::infinity());
      }
      thresholds_[k] = rounded;
    }
    thresholds_[255] = std::numeric_limits<float>::infinity();  // stops the step loop at 255
    bucketCode_.resize((std::bit_cast<std::uint32_t>(1.0F) >> kDroppedMantissaBits) + 1);
    for (std::size_t bucket = 0; bucket < bucketCode_.size(); ++bucket) {
      const float start =
          std::bit_cast<float>(static_cast<std::uint32_t>(bucket) << kDroppedMantissaBits);
      bucketCode_[bucket] = static_cast<std::uint8_t>(
          std::upper_bound(thresholds_.begin(), thresholds_.end() - 1, start) -
          thresholds_.begin());
    }
  }

  const std::array<float, 256>& thresholds() const { return thresholds_; }

  // `linear01` must lie in [0, 1].
  std::uint8_t encode(float linear01) const {
    unsigned code = bucketCode_[std::bit_cast<std::uint32_t>(linear01) >> kDroppedMantissaBits];
    while (linear01 >= thresholds_[code]) ++code;
    return static_cast<std::uint8_t>(code);
  }

 private:
  static constexpr int kDroppedMantissaBits = 15;
  std::array<float, 256> thresholds_{};
  std::vector<std::uint8_t> bucketCode_;
};

const SrgbEncoder& srgbEncoder() {
  static const SrgbEncoder encoder;
  return encoder;
}

std::uint8_t displayChannel(float linear, ToneMap mode, float exposure) {
  float value = linear * exposure;
  // !(value > 0) also catches NaN.
  value = !(value > 0.0F) ? 0.0F : std::min(value, kMaxLinear);
  return image_io::detail::srgbCode(std::clamp(toneMap(value, mode), 0.0F, 1.0F));
}

std::uint8_t linearAlpha8(float alpha) {
  const float clamped = !(alpha > 0.0F) ? 0.0F : std::min(alpha, 1.0F);
  return static_cast<std::uint8_t>(std::lround(clamped * 255.0F));
}

// ---- Files ----

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

Error fileError(int err, const std::string& action, const std::filesystem::path& path) {
  const ErrorCode code =
      (err == ENOENT || err == ENOTDIR) ? ErrorCode::NotFound : ErrorCode::Invalid;
  return Error(code, fmt::format("{}: {}", action, std::generic_category().message(err)),
               path.string());
}

// A sibling of `path`, unique per process and call, so concurrent writers never share it.
std::filesystem::path temporarySibling(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path temp = path;
  temp += fmt::format(".tmp-{}-{}", ::getpid(), counter.fetch_add(1));
  return temp;
}

// Removes the temporary file unless the write went through.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::filesystem::path path) : path_(std::move(path)) {}
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile() {
    if (!committed_) {
      std::error_code ignored;
      std::filesystem::remove(path_, ignored);
    }
  }
  const std::filesystem::path& path() const { return path_; }
  void commit() { committed_ = true; }

 private:
  std::filesystem::path path_;
  bool committed_ = false;
};

}  // namespace

// ---- Shared backend helpers ----

namespace image_io::detail {

namespace {

bool startsWith(const std::uint8_t* data, std::size_t size, std::string_view magic) {
  return size >= magic.size() && std::memcmp(data, magic.data(), magic.size()) == 0;
}

std::string lowerCase(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower;
}

// "prefix:name" keys in these namespaces belong to OpenImageIO (format-specific settings and
// metadata it synthesises on read); its writers drop or reinterpret them.
bool hasReservedPrefix(std::string_view key) {
  static const std::set<std::string, std::less<>> kPrefixes = {
      "oiio", "png",   "openexr",   "tiff", "jpeg",      "jpeg2000", "exif",  "gps",     "iptc",
      "xmp",  "smpte", "photoshop", "bmp",  "cineon",    "dds",      "dicom", "dpx",     "ffmpeg",
      "fits", "gif",   "heif",      "hdr",  "ico",       "iff",      "null",  "openvdb", "pnm",
      "psd",  "raw",   "rla",       "sgi",  "softimage", "targa",    "webp",  "zfile"};
  const std::size_t colon = key.find(':');
  return colon != std::string_view::npos && kPrefixes.contains(lowerCase(key.substr(0, colon)));
}

// OpenImageIO matches metadata names without regard to case, so these sets hold lower case.
//
// PNG: names OpenImageIO's writer turns into other chunks (tIME, pHYs, iCCP), or reads back under
// another name that it also writes verbatim (Artist, DocumentName, ImageDescription).
bool isReservedPngKey(const std::string& lowerKey) {
  static const std::set<std::string, std::less<>> kKeys = {
      "datetime",    "imagedescription", "artist",     "documentname", "xresolution",
      "yresolution", "resolutionunit",   "iccprofile", "name",         "compression"};
  return kKeys.contains(lowerKey);
}

// EXR: the header and standard attributes that are not strings (a string under one of these
// names breaks readers that expect the typed attribute), and the names OpenImageIO maps onto
// them or onto string attributes of other names.
bool isReservedExrKey(const std::string& lowerKey) {
  static const std::set<std::string, std::less<>> kKeys = {
      // Header and standard attributes (ImfHeader.h, ImfStandardAttributes.h).
      "channels", "compression", "datawindow", "displaywindow", "lineorder", "pixelaspectratio",
      "screenwindowcenter", "screenwindowwidth", "tiles", "type", "name", "version", "chunkcount",
      "view", "multiview", "maxsamplesperpixel", "chromaticities", "whiteluminance",
      "adoptedneutral", "xdensity", "utcoffset", "longitude", "latitude", "altitude", "focus",
      "exptime", "aperture", "isospeed", "envmap", "keycode", "timecode", "framespersecond",
      "worldtocamera", "worldtondc", "deepimagestate", "originaldatawindow", "dwacompressionlevel",
      "idmanifest", "cameratransform",
      // OpenImageIO's names for some of the above.
      "description", "imagedescription", "copyright", "datetime", "xresolution", "yresolution",
      "exposuretime", "fnumber", "worldtoscreen"};
  return kKeys.contains(lowerKey);
}

// Names OpenImageIO maps to its own names on read; the backends map them back, which only works
// for this exact spelling.
bool isOtherSpellingOfAlias(std::string_view key, const std::string& lowerKey,
                            MetadataFormat format) {
  static const std::array<std::string_view, 3> kPngAliases = {"Description", "Author", "Title"};
  static const std::array<std::string_view, 3> kExrAliases = {"comments", "owner", "capDate"};
  for (std::string_view alias : format == MetadataFormat::Png ? kPngAliases : kExrAliases) {
    if (lowerCase(alias) == lowerKey && alias != key) return true;
  }
  return false;
}

// PNG keyword rules (1..79 Latin-1 characters, no leading, trailing or doubled spaces),
// narrowed to printable ASCII so the key means the same in a UTF-8 EXR attribute name.
bool isValidKeyword(std::string_view key) {
  if (key.empty() || key.size() > 79 || key.front() == ' ' || key.back() == ' ') return false;
  if (key.find("  ") != std::string_view::npos) return false;
  return std::all_of(key.begin(), key.end(), [](char c) { return c >= 0x20 && c <= 0x7E; });
}

}  // namespace

std::string printable(std::string_view text) {
  std::string result(text);
  for (char& c : result) {
    if (c == '\n' || c == '\t') {
      c = ' ';
    } else if (c < 0x20 || c > 0x7E) {
      c = '?';
    }
  }
  return result;
}

FileKind sniffFileKind(const std::uint8_t* data, std::size_t size) {
  if (startsWith(data, size, "\x89PNG\r\n\x1a\n")) return FileKind::Png;
  if (startsWith(data, size, "\x76\x2f\x31\x01")) return FileKind::Exr;
  if (startsWith(data, size, "\xff\xd8\xff")) return FileKind::Jpeg;
  return FileKind::Unknown;
}

void checkDecodeSize(std::int64_t width, std::int64_t height, const std::string& what) {
  if (width <= 0 || height <= 0) {
    throw Error(ErrorCode::Invalid, fmt::format("image has no pixels ({}x{})", width, height),
                what);
  }
  if (width > kMaxDecodeDimension || height > kMaxDecodeDimension ||
      width * height > kMaxDecodePixels) {
    throw Error(ErrorCode::TooLarge,
                fmt::format("image is {}x{} pixels, over the limit of {} per side and {} Mi pixels",
                            width, height, kMaxDecodeDimension, kMaxDecodePixels >> 20),
                what);
  }
}

void checkImage8(const Image8& image) {
  if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
      image.pixels.size() !=
          static_cast<std::size_t>(image.width) * image.height * image.channels) {
    throw Error(ErrorCode::Internal,
                fmt::format("malformed 8-bit image: {}x{}, {} channels, {} bytes", image.width,
                            image.height, image.channels, image.pixels.size()));
  }
}

void checkImage8View(const Image8View& image) {
  if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
      image.pixels == nullptr) {
    throw Error(ErrorCode::Internal, fmt::format("malformed 8-bit image view: {}x{}, {} channels",
                                                 image.width, image.height, image.channels));
  }
}

void checkLinearRgbaView(const LinearRgbaView& image, bool halfFile) {
  if (image.width <= 0 || image.height <= 0 || image.pixels == nullptr ||
      (image.halfFloat && !halfFile)) {
    throw Error(
        ErrorCode::Internal,
        fmt::format("malformed linear image view: {}x{}, {} pixels for a {} file", image.width,
                    image.height, image.halfFloat ? "half" : "float", halfFile ? "half" : "float"));
  }
}

const std::array<float, 256>& srgbThresholds() { return srgbEncoder().thresholds(); }

std::uint8_t srgbCode(float linear01) { return srgbEncoder().encode(linear01); }

const std::array<float, 256>& srgbToLinearTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> values{};
    for (std::size_t code = 0; code < values.size(); ++code) {
      const float c = static_cast<float>(code) / 255.0F;
      values[code] = c <= 0.04045F ? c / 12.92F : std::pow((c + 0.055F) / 1.055F, 2.4F);
    }
    return values;
  }();
  return table;
}

void checkPngCompression(int level) {
  if (level < 0 || level > 9) {
    throw Error(ErrorCode::Invalid,
                fmt::format("PNG compression level {} is outside zlib's 0..9", level));
  }
}

void checkFloatImage(const FloatImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
    throw Error(ErrorCode::Internal, fmt::format("malformed float image: {}x{}, {} floats",
                                                 image.width, image.height, image.rgba.size()));
  }
}

namespace {

std::uint32_t bigEndian32(const std::uint8_t* p) {
  return (static_cast<std::uint32_t>(p[0]) << 24) | (p[1] << 16) | (p[2] << 8) | p[3];
}

// Bits per pixel from IHDR's bit depth and colour type; 0 for an invalid colour type.
std::uint64_t pngBitsPerPixel(std::uint8_t bitDepth, std::uint8_t colorType) {
  switch (colorType) {
    case 0:  // grey
    case 3:  // palette
      return bitDepth;
    case 2:  // RGB
      return std::uint64_t{3} * bitDepth;
    case 4:  // grey + alpha
      return std::uint64_t{2} * bitDepth;
    case 6:  // RGBA
      return std::uint64_t{4} * bitDepth;
    default:
      return 0;
  }
}

// Deflate cannot expand one byte into more than 1032, so image data shorter than this cannot
// hold the pixels IHDR claims: a 1 KB file claiming 16384 x 16384 would otherwise cost a 1 GiB
// buffer before the decoder notices.
void checkPngDataCanHoldImage(const std::uint8_t* header, std::uint64_t compressedBytes,
                              const std::string& what) {
  const std::uint64_t width = bigEndian32(header);
  const std::uint64_t height = bigEndian32(header + 4);
  checkDecodeSize(static_cast<std::int64_t>(width), static_cast<std::int64_t>(height), what);
  const std::uint64_t bits = pngBitsPerPixel(header[8], header[9]);
  const std::uint64_t rawBytes = (width * height * bits + 7) / 8;  // filter bytes not counted
  if (rawBytes > (compressedBytes + 1) * 1032) {
    throw Error(ErrorCode::Invalid,
                fmt::format("broken PNG image: {} bytes of image data cannot hold {}x{} pixels",
                            compressedBytes, width, height),
                what);
  }
}

}  // namespace

void checkPngChunks(const std::uint8_t* data, std::size_t size, const std::string& what) {
  std::size_t position = 8;  // after the signature
  const std::uint8_t* header = nullptr;
  std::uint64_t compressedBytes = 0;
  while (size - position >= 8) {
    const std::uint8_t* chunk = data + position;
    const std::uint32_t length = bigEndian32(chunk);
    const std::string_view type(reinterpret_cast<const char*>(chunk + 4), 4);
    // Length, type, data and CRC; the spec caps the length at 2^31 - 1.
    const std::size_t available = size - position;
    if (length > 0x7FFFFFFFU || available < 12 || length > available - 12) {
      throw Error(ErrorCode::Invalid,
                  fmt::format("broken PNG image: chunk '{}' claims {} bytes, more than the file "
                              "holds",
                              printable(type), length),
                  what);
    }
    if (type == "IHDR" && length == 13 && header == nullptr) header = chunk + 8;
    if (type == "IDAT") compressedBytes += length;
    if (type == "IEND") {
      // Without a valid IHDR libpng reports the error itself.
      if (header != nullptr) checkPngDataCanHoldImage(header, compressedBytes, what);
      return;
    }
    position += 12 + static_cast<std::size_t>(length);
  }
  // Truncated. Refused here because OpenImageIO's PNG read callback leaks a string each time it
  // hits the end of the data (it longjmps over it), and the lean backend would fail anyway.
  throw Error(ErrorCode::Invalid, "broken PNG image: truncated (no IEND chunk)", what);
}

namespace {

// Bounds-checked little-endian reader over an OpenEXR header.
class ExrHeaderReader {
 public:
  ExrHeaderReader(const std::uint8_t* data, std::size_t size, const std::string& what)
      : data_(data), size_(size), what_(what) {}

  std::size_t remaining() const { return size_ - position_; }
  std::uint8_t peek() const {
    need(1);
    return data_[position_];
  }
  std::uint32_t uint32() {
    need(4);
    const std::uint8_t* p = data_ + position_;
    position_ += 4;
    return p[0] | (p[1] << 8) | (p[2] << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
  }
  std::int32_t int32() { return static_cast<std::int32_t>(uint32()); }
  // A NUL-terminated name of at most `maxLength` characters.
  std::string_view name(std::size_t maxLength) {
    const auto* begin = reinterpret_cast<const char*>(data_ + position_);
    const std::size_t limit = std::min(remaining(), maxLength + 1);
    const std::size_t length = std::string_view(begin, limit).find('\0');
    if (length == std::string_view::npos) fail("unterminated or overlong attribute name");
    position_ += length + 1;
    return {begin, length};
  }
  void skip(std::size_t count) {
    need(count);
    position_ += count;
  }
  [[noreturn]] void fail(const std::string& reason) const {
    throw Error(ErrorCode::Invalid, "broken OpenEXR header: " + reason, what_);
  }

 private:
  void need(std::size_t count) const {
    if (count > remaining()) fail("truncated");
  }

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
  const std::string& what_;
};

std::int64_t ceilDivide(std::int64_t a, std::int64_t b) { return (a + b - 1) / b; }

// One part's header, up to and including its terminating NUL.
void checkExrPartHeader(ExrHeaderReader& reader, std::size_t maxNameLength, std::size_t fileSize,
                        const std::string& what) {
  std::int64_t width = 0;
  std::int64_t height = 0;
  std::int64_t tileWidth = 0;
  std::int64_t tileHeight = 0;
  for (;;) {
    const std::string_view name = reader.name(maxNameLength);
    if (name.empty()) break;
    const std::string_view type = reader.name(maxNameLength);
    const std::int32_t size = reader.int32();
    if (size < 0 || static_cast<std::size_t>(size) > reader.remaining()) {
      reader.fail(fmt::format("attribute '{}' claims {} bytes, more than the file holds",
                              printable(name), size));
    }
    if (name == "dataWindow" && type == "box2i" && size == 16) {
      const std::int64_t xMin = reader.int32(), yMin = reader.int32();
      width = std::int64_t{reader.int32()} - xMin + 1;
      height = std::int64_t{reader.int32()} - yMin + 1;
      checkDecodeSize(width, height, what);
    } else if (name == "tiles" && type == "tiledesc" && size == 9) {
      tileWidth = reader.uint32();
      tileHeight = reader.uint32();
      reader.skip(1);
      if (tileWidth == 0 || tileHeight == 0) reader.fail("zero tile size");
    } else if (name == "chunkCount" && type == "int" && size == 4) {
      const std::int32_t chunks = reader.int32();
      if (chunks < 0 || static_cast<std::size_t>(chunks) > fileSize / 8) {
        reader.fail(fmt::format("{} chunks cannot fit in the file", chunks));
      }
    } else {
      reader.skip(static_cast<std::size_t>(size));
    }
  }
  if (width == 0) reader.fail("no dataWindow");
  // Each tile has an 8-byte entry in the file's offset table, which OpenEXR allocates up front.
  if (tileWidth > 0 && ceilDivide(width, tileWidth) * ceilDivide(height, tileHeight) >
                           static_cast<std::int64_t>(fileSize / 8)) {
    reader.fail("more tiles than the file holds");
  }
}

}  // namespace

void checkExrHeader(const std::uint8_t* data, std::size_t size, const std::string& what) {
  ExrHeaderReader reader(data, size, what);
  reader.skip(4);  // magic number, checked by the caller's sniffing
  const std::uint32_t version = reader.uint32();
  const bool multipart = (version & 0x1000U) != 0;
  const std::size_t maxNameLength = (version & 0x400U) != 0 ? 255 : 31;
  do {
    checkExrPartHeader(reader, maxNameLength, size, what);
  } while (multipart && reader.peek() != 0);  // an empty header ends the list
}

bool isReservedMetadataKey(std::string_view key, MetadataFormat format) {
  if (hasReservedPrefix(key)) return true;
  const std::string lowerKey = lowerCase(key);
  if (isOtherSpellingOfAlias(key, lowerKey, format)) return true;
  return format == MetadataFormat::Png ? isReservedPngKey(lowerKey) : isReservedExrKey(lowerKey);
}

ImageMetadata withCaptureDate(const ImageMetadata& metadata) {
  const bool hasDate = std::any_of(metadata.begin(), metadata.end(),
                                   [](const auto& entry) { return entry.first == "capDate"; });
  if (hasDate) return metadata;
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  ImageMetadata stamped = metadata;
  stamped.emplace_back("capDate", fmt::format("{:04}:{:02}:{:02} {:02}:{:02}:{:02}",
                                              local.tm_year + 1900, local.tm_mon + 1, local.tm_mday,
                                              local.tm_hour, local.tm_min, local.tm_sec));
  return stamped;
}

void checkMetadata(const ImageMetadata& metadata, MetadataFormat format) {
  const char* formatName = format == MetadataFormat::Png ? "PNG" : "OpenEXR";
  std::set<std::string_view> seen;
  for (const auto& [key, value] : metadata) {
    if (!isValidKeyword(key)) {
      throw Error(ErrorCode::Invalid,
                  fmt::format("metadata key '{}' is not 1..79 printable ASCII characters without "
                              "leading, trailing or doubled spaces",
                              key),
                  "metadata");
    }
    if (isReservedMetadataKey(key, format)) {
      throw Error(ErrorCode::Invalid,
                  fmt::format("metadata key '{}' is reserved in {} files", key, formatName),
                  "metadata");
    }
    if (!seen.insert(key).second) {
      throw Error(ErrorCode::Invalid, fmt::format("duplicate metadata key '{}'", key), "metadata");
    }
    if (value.find('\0') != std::string::npos) {
      throw Error(ErrorCode::Invalid,
                  fmt::format("metadata value of '{}' contains a NUL byte", key), "metadata");
    }
  }
}

Image8 expandToRgba8(int width, int height, int channels, const std::uint8_t* pixels) {
  Image8 rgba{width, height, 4, {}};
  const std::size_t count = static_cast<std::size_t>(width) * height;
  rgba.pixels.resize(count * 4);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* in = pixels + i * channels;
    std::uint8_t* out = &rgba.pixels[i * 4];
    const bool grey = channels <= 2;
    out[0] = in[0];
    out[1] = grey ? in[0] : in[1];
    out[2] = grey ? in[0] : in[2];
    out[3] = channels == 2 ? in[1] : channels == 4 ? in[3] : 255;
  }
  return rgba;
}

}  // namespace image_io::detail

// ---- File I/O ----

namespace image_io {

// Writes a sibling temporary file and renames it over `path`, so readers never see half a file.
void writeFile(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  TemporaryFile temp(temporarySibling(path));
  FilePtr file(std::fopen(temp.path().c_str(), "wb"));
  if (!file) throw fileError(errno, "cannot create file", path);
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file.get()) != bytes.size()) {
    throw fileError(errno, "cannot write file", path);
  }
  // fclose flushes: a full disk shows up here.
  if (std::fclose(file.release()) != 0) throw fileError(errno, "cannot write file", path);
  std::error_code ec;
  std::filesystem::rename(temp.path(), path, ec);
  if (ec) throw fileError(ec.value(), "cannot write file", path);
  temp.commit();
}

std::vector<std::uint8_t> readFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(ErrorCode::Invalid, "is a directory, not a file", path.string());
  }
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) throw fileError(errno, "cannot open file", path);
  std::vector<std::uint8_t> bytes;
  std::array<std::uint8_t, 1 << 16> chunk{};
  while (const std::size_t count = std::fread(chunk.data(), 1, chunk.size(), file.get())) {
    bytes.insert(bytes.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(count));
  }
  if (std::ferror(file.get())) throw fileError(errno, "cannot read file", path);
  return bytes;
}

}  // namespace image_io

// ---- Display conversion and request-level encoding ----

Image8 toDisplay8(const FloatImage& linear, ToneMap toneMap, float exposure, bool keepAlpha) {
  image_io::detail::checkFloatImage(linear);
  const int channels = keepAlpha ? 4 : 3;
  Image8 display{linear.width, linear.height, channels, {}};
  const std::size_t count = static_cast<std::size_t>(linear.width) * linear.height;
  display.pixels.resize(count * channels);
  for (std::size_t i = 0; i < count; ++i) {
    const float* in = &linear.rgba[i * 4];
    std::uint8_t* out = &display.pixels[i * channels];
    for (int c = 0; c < 3; ++c) out[c] = displayChannel(in[c], toneMap, exposure);
    if (keepAlpha) out[3] = linearAlpha8(in[3]);
  }
  return display;
}

std::vector<std::uint8_t> encodeImage(const FloatImage& linear, const OutputSettings& output,
                                      const ImageMetadata& metadata) {
  switch (output.format) {
    case ImageFormat::Png:
      return image_io::encodePng(
          toDisplay8(linear, output.toneMap, output.exposure, output.transparentBackground),
          metadata, output.pngCompression);
    case ImageFormat::ExrHalf:
      return image_io::encodeExr(linear, true, metadata);
    case ImageFormat::ExrFloat:
      return image_io::encodeExr(linear, false, metadata);
  }
  throw Error(ErrorCode::Internal, "unknown output image format");
}

namespace image_io {

std::vector<std::uint8_t> encodeExr(const FloatImage& image, bool halfFloat,
                                    const ImageMetadata& metadata) {
  detail::checkFloatImage(image);
  return encodeExr(LinearRgbaView{image.width, image.height, false, image.rgba.data()}, halfFloat,
                   metadata);
}

}  // namespace image_io

const char* mimeType(ImageFormat format) {
  return format == ImageFormat::Png ? "image/png" : "image/x-exr";
}

const char* fileExtension(ImageFormat format) {
  return format == ImageFormat::Png ? ".png" : ".exr";
}

}  // namespace lgh
