// zip_writer.hpp: archives written in memory, read back with libzip (with its consistency
// checks) and compared entry by entry, byte for byte: names, order, contents, compression method.
#include <gtest/gtest.h>
#include <zip.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "api_error.hpp"
#include "zip_writer.hpp"

namespace lghd {
namespace {

struct Entry {
  std::string name;
  std::vector<std::uint8_t> bytes;
  std::uint16_t method = ZIP_CM_STORE;
  std::uint64_t compressedSize = 0;
  std::string comment;
};

// Every entry of the archive in `bytes`, in order. Fails the test when libzip refuses it.
std::vector<Entry> readArchive(const std::string& bytes) {
  std::vector<Entry> entries;
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
  EXPECT_NE(source, nullptr) << zip_error_strerror(&error);
  if (source == nullptr) return entries;
  zip_t* archive = zip_open_from_source(source, ZIP_RDONLY | ZIP_CHECKCONS, &error);
  if (archive == nullptr) {
    ADD_FAILURE() << "libzip cannot open the archive: " << zip_error_strerror(&error);
    zip_source_free(source);
    zip_error_fini(&error);
    return entries;
  }
  zip_error_fini(&error);
  const zip_int64_t count = zip_get_num_entries(archive, 0);
  for (zip_int64_t i = 0; i < count; ++i) {
    const auto index = static_cast<zip_uint64_t>(i);
    zip_stat_t stat;
    zip_stat_init(&stat);
    if (zip_stat_index(archive, index, 0, &stat) != 0) {
      ADD_FAILURE() << "zip_stat_index " << i << ": " << zip_strerror(archive);
      break;
    }
    Entry entry{stat.name, std::vector<std::uint8_t>(stat.size), stat.comp_method, stat.comp_size};
    zip_uint32_t commentLength = 0;
    if (const char* comment = zip_file_get_comment(archive, index, &commentLength, 0)) {
      entry.comment.assign(comment, commentLength);
    }
    zip_file_t* file = zip_fopen_index(archive, index, 0);
    if (file == nullptr) {
      ADD_FAILURE() << "zip_fopen_index " << i << ": " << zip_strerror(archive);
      break;
    }
    const zip_int64_t read = zip_fread(file, entry.bytes.data(), entry.bytes.size());
    EXPECT_EQ(read, static_cast<zip_int64_t>(entry.bytes.size())) << entry.name;
    zip_fclose(file);
    entries.push_back(std::move(entry));
  }
  zip_close(archive);  // read-only: frees the archive and its source
  return entries;
}

std::vector<std::uint8_t> randomBytes(std::size_t size, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::uint8_t> bytes(size);
  for (auto& b : bytes) b = static_cast<std::uint8_t>(byte(random));
  return bytes;
}

std::vector<std::uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

TEST(ZipWriter, EntriesReadBackByteForByte) {
  const std::vector<std::uint8_t> png = randomBytes(70'000, 1);  // incompressible, like a PNG
  const std::vector<std::uint8_t> zeros(4096, 0);
  const std::vector<std::uint8_t> small = {0x89, 'P', 'N', 'G', 0x00, 0x0D, 0x0A, 0x1A, 0x0A};
  std::string text;
  for (int i = 0; i < 200; ++i) {
    text += R"({"index": )" + std::to_string(i) + R"(, "error": "x"})" + "\n";
  }

  ZipWriter zip;
  zip.addStored("a_front.png", png);
  zip.addStored("dir/zeros.bin", zeros);
  zip.addStored("tiny.png", small);
  zip.addStored("empty.png", {});
  zip.addStored("naïve_☃.png", small);  // names are UTF-8
  zip.addDeflated("errors.json", text);
  const std::string archive = zip.finish();
  ASSERT_FALSE(archive.empty());
  EXPECT_EQ(archive.rfind("PK\x03\x04", 0), 0U) << "a ZIP starts with a local file header";

  const std::vector<Entry> entries = readArchive(archive);
  const std::vector<std::pair<std::string, std::vector<std::uint8_t>>> expected{
      {"a_front.png", png}, {"dir/zeros.bin", zeros}, {"tiny.png", small},
      {"empty.png", {}},    {"naïve_☃.png", small},   {"errors.json", bytesOf(text)},
  };
  ASSERT_EQ(entries.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(entries[i].name, expected[i].first) << i;
    EXPECT_EQ(entries[i].bytes, expected[i].second) << expected[i].first;
  }
}

// Images are stored (PNG is compressed already); text members are deflated.
TEST(ZipWriter, ImagesStoredTextDeflated) {
  const std::vector<std::uint8_t> image = randomBytes(10'000, 2);
  const std::string text(20'000, 'a');
  ZipWriter zip;
  zip.addStored("image.png", image);
  zip.addDeflated("errors.json", text);
  const std::vector<Entry> entries = readArchive(zip.finish());
  ASSERT_EQ(entries.size(), 2U);
  EXPECT_EQ(entries[0].method, ZIP_CM_STORE);
  EXPECT_EQ(entries[0].compressedSize, image.size());
  EXPECT_EQ(entries[1].method, ZIP_CM_DEFLATE);
  EXPECT_LT(entries[1].compressedSize, text.size() / 10) << "20 000 equal bytes deflate well";
  EXPECT_EQ(entries[1].bytes, bytesOf(text));
}

// A member's comment (the GPU that rendered a thumbnail) reads back from the central directory;
// members without one have none.
TEST(ZipWriter, MemberCommentsReadBack) {
  ZipWriter zip;
  zip.addStored("a.png", randomBytes(100, 4), R"({"gpu":1})");
  zip.addStored("b.png", randomBytes(100, 5));
  zip.addDeflated("errors.json", "[]");
  const std::vector<Entry> entries = readArchive(zip.finish());
  ASSERT_EQ(entries.size(), 3U);
  EXPECT_EQ(entries[0].comment, R"({"gpu":1})");
  EXPECT_EQ(entries[1].comment, "");
  EXPECT_EQ(entries[2].comment, "");
  EXPECT_EQ(entries[0].bytes, randomBytes(100, 4));
}

// The writer copies the bytes it is given: the caller's buffers may go before finish().
TEST(ZipWriter, KeepsItsOwnCopyUntilFinish) {
  ZipWriter zip;
  {
    std::vector<std::uint8_t> bytes = randomBytes(1000, 3);
    zip.addStored("one.png", bytes);
    std::string text = "first";
    zip.addDeflated("two.txt", text);
    bytes.assign(bytes.size(), 0);
    text = "changed";
  }
  const std::vector<Entry> entries = readArchive(zip.finish());
  ASSERT_EQ(entries.size(), 2U);
  EXPECT_EQ(entries[0].bytes, randomBytes(1000, 3));
  EXPECT_EQ(entries[1].bytes, bytesOf("first"));
}

TEST(ZipWriter, ManyEntries) {
  ZipWriter zip;
  for (int i = 0; i < 300; ++i) {
    zip.addStored("thumb_" + std::to_string(i) + ".png",
                  randomBytes(static_cast<std::size_t>(i), i));
  }
  const std::vector<Entry> entries = readArchive(zip.finish());
  ASSERT_EQ(entries.size(), 300U);
  for (int i = 0; i < 300; ++i) {
    EXPECT_EQ(entries[i].name, "thumb_" + std::to_string(i) + ".png");
    EXPECT_EQ(entries[i].bytes, randomBytes(static_cast<std::size_t>(i), i)) << i;
  }
}

// A name given twice is a bug in the caller (thumbnail names are unique in a batch): a 500, not a
// silently overwritten entry.
TEST(ZipWriter, DuplicateNameIsAnInternalError) {
  ZipWriter zip;
  zip.addStored("same.png", {1, 2, 3});
  try {
    zip.addStored("same.png", {4, 5, 6});
    FAIL() << "no exception";
  } catch (const ApiError& error) {
    EXPECT_EQ(error.status(), 500);
    EXPECT_NE(error.message().find("same.png"), std::string::npos) << error.message();
  }
}

}  // namespace
}  // namespace lghd
