// Backend-independent helpers shared by backend_oiio.cpp and backend_lean.cpp: input checks,
// the metadata key rules, decode size limits, format sniffing. Keeping these in one place is what
// makes the two backends accept and reject the same inputs.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "lgh/image.hpp"

namespace lgh::image_io::detail {

// Decoded images larger than this are refused (ErrorCode::TooLarge) before any pixel buffer is
// allocated: a 20-byte PNG header can claim a 4 GiB image.
inline constexpr std::int64_t kMaxDecodeDimension = 16384;
inline constexpr std::int64_t kMaxDecodePixels = 256LL * 1024 * 1024;

// `text` with bytes outside printable ASCII replaced by '?': messages quoting damaged files (chunk
// and attribute names, library errors) end up in JSON error bodies, which need valid UTF-8.
std::string printable(std::string_view text);

enum class FileKind { Png, Exr, Jpeg, Unknown };

// Recognises PNG, OpenEXR and JPEG by their magic numbers.
FileKind sniffFileKind(const std::uint8_t* data, std::size_t size);

// Throws Invalid for a non-positive size, TooLarge past the limits above.
void checkDecodeSize(std::int64_t width, std::int64_t height, const std::string& what);

// Walks the PNG chunk list: throws Invalid when a chunk claims more bytes than the data holds
// (OpenImageIO's PNG reader keeps feeding libpng past the end of the data, so a damaged length of
// a gigabyte costs tens of seconds of skipping), or when the image data is too short to inflate
// to the size IHDR claims (a decompression bomb's buffer is never allocated), or when the data
// ends before IEND.
void checkPngChunks(const std::uint8_t* data, std::size_t size, const std::string& what);

// Walks the OpenEXR header(s) without allocating: throws Invalid when an attribute claims more
// bytes than the data holds, or tiles or chunks need a bigger offset table than the data holds, and
// TooLarge when a part's dataWindow is over the decode limits. OpenEXR 3.1 trusts these numbers
// and allocates what a damaged header claims (gigabytes for one string attribute).
void checkExrHeader(const std::uint8_t* data, std::size_t size, const std::string& what);

// Throws Internal: a malformed in-memory image is a caller bug, not bad user input.
void checkImage8(const Image8& image);
void checkImage8View(const Image8View& image);
// A half-float view only makes a half file (nothing widens halves to floats on the way out).
void checkLinearRgbaView(const LinearRgbaView& image, bool halfFile);
void checkPngCompression(int level);
void checkFloatImage(const FloatImage& image);

enum class MetadataFormat { Png, Exr };

// True for keys that one of the backends cannot store verbatim (OpenImageIO renames or drops
// them, matching names without regard to case, or the format reserves them for typed
// attributes). Both backends refuse them, and the OIIO
// backend's decode drops them, so that metadata round-trips the same way in both.
bool isReservedMetadataKey(std::string_view key, MetadataFormat format);
// `metadata` plus "capDate" (local time, "YYYY:MM:DD hh:mm:ss") unless it has one. OpenImageIO's
// EXR writer always stamps the date when given none, so both backends do, and a caller that wants
// reproducible files passes its own capDate.
ImageMetadata withCaptureDate(const ImageMetadata& metadata);
// Throws Invalid naming the key: empty or over 79 characters, non-printable-ASCII, leading,
// trailing or doubled spaces (PNG keyword rules, applied to EXR too), reserved, or a value with a
// NUL byte.
void checkMetadata(const ImageMetadata& metadata, MetadataFormat format);

// threshold[k] is the smallest float whose sRGB encoding rounds to code k + 1: the inverse OETF of
// (k + 0.5) / 255, rounded up to a float; threshold[255] is +infinity. A linear value in [0, 1]
// encodes to the number of thresholds at or below it. The GPU's display transform counts against
// the same table (glsl/include/display_transform.glsl), so both round alike.
const std::array<float, 256>& srgbThresholds();
// The code a linear value in [0, 1] encodes to by those thresholds (the CPU's display transform).
std::uint8_t srgbCode(float linear01);
// Each sRGB code's linear value (the sRGB EOTF of code / 255).
const std::array<float, 256>& srgbToLinearTable();

// 1..4 interleaved 8-bit channels (grey, grey+alpha, RGB, RGBA) to RGBA; alpha 255 when absent.
Image8 expandToRgba8(int width, int height, int channels, const std::uint8_t* pixels);

}  // namespace lgh::image_io::detail
