// Response headers built from request data stay under their caps, as valid JSON that says what
// was left out.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "capped_header.hpp"

namespace lghd {
namespace {

TEST(CappedHeader, ShortListsAreUnchanged) {
  EXPECT_EQ(cappedJsonArray({"a", "b"}, 2048), R"(["a","b"])");
  EXPECT_EQ(cappedJsonObject({{"k", "v"}}, 1024), R"({"k":"v"})");
}

TEST(CappedHeader, LongListsKeepWholeItemsAndSayHowManyWereLeftOut) {
  std::vector<std::string> items;
  for (int i = 0; i < 500; ++i) items.push_back("warning number " + std::to_string(i) + " é");
  const std::string header = cappedJsonArray(items, 2048);
  EXPECT_LE(header.size(), 2048U);
  for (char c : header) EXPECT_LT(static_cast<unsigned char>(c), 0x80);  // ASCII only
  const nlohmann::json parsed = nlohmann::json::parse(header);
  ASSERT_GT(parsed.size(), 2U);
  EXPECT_EQ(parsed[0], items[0]);
  const std::string marker = parsed.back();
  const std::size_t kept = parsed.size() - 1;
  EXPECT_EQ(marker.rfind("... " + std::to_string(items.size() - kept) + " more", 0), 0U) << marker;

  std::map<std::string, std::string> entries;
  for (int i = 0; i < 200; ++i) entries["topic" + std::to_string(i)] = std::string(20, 'v');
  const std::string object = cappedJsonObject(entries, 1024);
  EXPECT_LE(object.size(), 1024U);
  EXPECT_TRUE(nlohmann::json::parse(object).contains("truncated"));
}

}  // namespace
}  // namespace lghd
