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

  // The bytes are copied; libzip reads them when the archive is finished.
  void addStored(const std::string& name, std::vector<std::uint8_t> bytes);
  void addDeflated(const std::string& name, const std::string& text);
  // Writes the archive and returns its bytes; the writer is spent afterwards.
  std::string finish();

 private:
  void add(const std::string& name, std::vector<std::uint8_t> bytes, bool compress);

  struct Archive;
  std::unique_ptr<Archive> archive_;
  std::vector<std::unique_ptr<std::vector<std::uint8_t>>> members_;  // alive until finish()
};

}  // namespace lghd
