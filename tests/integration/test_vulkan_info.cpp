// The Vulkan probe behind /v1/info, against the real loader and Mesa's lavapipe.
#include <gtest/gtest.h>

#include <cstdlib>

#include "lgh/vulkan_info.hpp"

namespace lgh::test {
namespace {

TEST(VulkanInfo, FindsLavapipeWithItsVersionsAndRayTracingFlags) {
  const VulkanInfo info = probeVulkan();
  ASSERT_TRUE(info.available) << info.error;
  EXPECT_TRUE(info.error.empty());
  EXPECT_EQ(info.loaderVersion.substr(0, 2), "1.");
  bool foundLavapipe = false;
  for (const auto& device : info.devices) {
    EXPECT_FALSE(device.name.empty());
    EXPECT_EQ(device.apiVersion.substr(0, 2), "1.");
    if (device.name.find("llvmpipe") != std::string::npos) {
      foundLavapipe = true;
      EXPECT_EQ(device.type, "cpu");
      EXPECT_EQ(device.vendorId, 0x10005U) << "Mesa's vendor id";
    }
  }
  EXPECT_TRUE(foundLavapipe) << info.toJson().dump(2);
  const auto json = info.toJson();
  EXPECT_EQ(json.at("devices").size(), info.devices.size());
  EXPECT_FALSE(json.contains("error"));
}

TEST(VulkanInfo, NoDriverIsReportedNotThrown) {
  // An ICD list naming no file: the loader finds no driver, and the probe says so.
  ASSERT_EQ(setenv("VK_ICD_FILENAMES", "/nonexistent/icd.json", 1), 0);
  ASSERT_EQ(setenv("VK_DRIVER_FILES", "/nonexistent/icd.json", 1), 0);
  const VulkanInfo info = probeVulkan();
  unsetenv("VK_ICD_FILENAMES");
  unsetenv("VK_DRIVER_FILES");
  EXPECT_FALSE(info.available);
  EXPECT_FALSE(info.error.empty());
  EXPECT_TRUE(info.devices.empty());
  EXPECT_EQ(info.toJson().at("available"), false);
}

}  // namespace
}  // namespace lgh::test
