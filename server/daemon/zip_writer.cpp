#include "zip_writer.hpp"

#include <zip.h>

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "api_error.hpp"

namespace lghd {
namespace {

[[noreturn]] void fail(const std::string& what, zip_error_t* error) {
  const std::string message = fmt::format("ZIP: {}: {}", what, zip_error_strerror(error));
  zip_error_fini(error);
  throw internalError(message);
}

[[noreturn]] void fail(const std::string& what, zip_t* archive) {
  throw internalError(fmt::format("ZIP: {}: {}", what, zip_strerror(archive)));
}

}  // namespace

// The memory source holds the archive's bytes; `zip` writes into it. The source is kept (one
// extra reference) so that it outlives zip_close and can be read back.
struct ZipWriter::Archive {
  zip_source_t* source = nullptr;
  zip_t* zip = nullptr;

  Archive() {
    zip_error_t error;
    zip_error_init(&error);
    source = zip_source_buffer_create(nullptr, 0, 0, &error);
    if (source == nullptr) fail("creating the memory buffer", &error);
    zip = zip_open_from_source(source, ZIP_TRUNCATE, &error);
    if (zip == nullptr) {
      zip_source_free(source);
      fail("opening the archive", &error);
    }
    zip_source_keep(source);
    zip_error_fini(&error);
  }
  ~Archive() {
    if (zip != nullptr) zip_discard(zip);
    zip_source_free(source);
  }
  Archive(const Archive&) = delete;
  Archive& operator=(const Archive&) = delete;
};

ZipWriter::ZipWriter() : archive_(std::make_unique<Archive>()) {}
ZipWriter::~ZipWriter() = default;

void ZipWriter::add(const std::string& name, std::vector<std::uint8_t> bytes, bool compress,
                    const std::string& comment) {
  auto& member =
      members_.emplace_back(std::make_unique<std::vector<std::uint8_t>>(std::move(bytes)));
  zip_source_t* source = zip_source_buffer(archive_->zip, member->data(), member->size(), 0);
  if (source == nullptr) fail("adding " + name, archive_->zip);
  const zip_int64_t index = zip_file_add(archive_->zip, name.c_str(), source, ZIP_FL_ENC_UTF_8);
  if (index < 0) {
    zip_source_free(source);
    fail("adding " + name, archive_->zip);
  }
  const zip_int32_t method = compress ? ZIP_CM_DEFLATE : ZIP_CM_STORE;
  if (zip_set_file_compression(archive_->zip, static_cast<zip_uint64_t>(index), method, 0) != 0) {
    fail("setting the compression of " + name, archive_->zip);
  }
  if (!comment.empty() &&
      zip_file_set_comment(archive_->zip, static_cast<zip_uint64_t>(index), comment.data(),
                           static_cast<zip_uint16_t>(std::min<std::size_t>(comment.size(), 0xffff)),
                           ZIP_FL_ENC_UTF_8) != 0) {
    fail("setting the comment of " + name, archive_->zip);
  }
}

void ZipWriter::addStored(const std::string& name, std::vector<std::uint8_t> bytes,
                          const std::string& comment) {
  add(name, std::move(bytes), false, comment);
}

void ZipWriter::addDeflated(const std::string& name, const std::string& text) {
  add(name, std::vector<std::uint8_t>(text.begin(), text.end()), true, "");
}

std::string ZipWriter::finish() {
  if (zip_close(archive_->zip) != 0) fail("writing the archive", archive_->zip);
  archive_->zip = nullptr;
  zip_source_t* source = archive_->source;
  if (zip_source_open(source) != 0) throw internalError("ZIP: cannot read the archive back");
  zip_source_seek(source, 0, SEEK_END);
  const zip_int64_t size = zip_source_tell(source);
  zip_source_seek(source, 0, SEEK_SET);
  std::string bytes(static_cast<std::size_t>(std::max<zip_int64_t>(size, 0)), '\0');
  const zip_int64_t read = zip_source_read(source, bytes.data(), bytes.size());
  zip_source_close(source);
  if (read != static_cast<zip_int64_t>(bytes.size())) {
    throw internalError("ZIP: short read of the finished archive");
  }
  return bytes;
}

}  // namespace lghd
