// A ZIP archive built in memory with libzip. Images go in stored (PNG is compressed already);
// text members are deflated.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lghd {

class ZipWriter {
 public:
  ZipWriter();
  ~ZipWriter();
  ZipWriter(const ZipWriter&) = delete;
  ZipWriter& operator=(const ZipWriter&) = delete;

  // The bytes are copied; libzip reads them when the archive is finished. A non-empty comment
  // becomes the member's file comment in the central directory (`zipinfo -v`, Python's
  // ZipInfo.comment).
  void addStored(const std::string& name, std::vector<std::uint8_t> bytes,
                 const std::string& comment = "");
  void addDeflated(const std::string& name, const std::string& text);
  // Writes the archive and returns its bytes; the writer is spent afterwards.
  std::string finish();

 private:
  void add(const std::string& name, std::vector<std::uint8_t> bytes, bool compress,
           const std::string& comment);

  struct Archive;
  std::unique_ptr<Archive> archive_;
  std::vector<std::unique_ptr<std::vector<std::uint8_t>>> members_;  // alive until finish()
};

}  // namespace lghd
