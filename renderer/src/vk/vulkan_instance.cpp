#include "vk/vulkan_instance.hpp"

#include <fmt/format.h>

#include "lgh/error.hpp"
#include "vk/vulkan_errors.hpp"

namespace lgh::vk {
namespace {

constexpr std::uint32_t kApiVersion = VK_API_VERSION_1_2;

std::string versionText(std::uint32_t version) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version),
                     VK_API_VERSION_PATCH(version));
}

::vk::raii::Context* openLoader() {
  try {
    // Never destroyed: closing the loader unloads the driver with it, and drivers that share code
    // with their GL driver (NVIDIA's) do not survive that in the middle of a process.
    return new ::vk::raii::Context();  // NOLINT(*-owning-memory): lives as long as the process
  } catch (const std::exception& error) {
    throw Error(ErrorCode::Unavailable,
                fmt::format("no Vulkan loader (libvulkan.so.1): {}", error.what()));
  }
}

}  // namespace

const ::vk::raii::Context& vulkanLoader() {
  static ::vk::raii::Context* const loader = openLoader();
  return *loader;
}

::vk::raii::Instance createInstance() {
  const ::vk::raii::Context& loader = vulkanLoader();
  const std::uint32_t loaderVersion = loader.enumerateInstanceVersion();
  if (loaderVersion < kApiVersion) {
    throw Error(ErrorCode::Unavailable,
                fmt::format("the Vulkan loader is version {}; the shadow tracer needs 1.2",
                            versionText(loaderVersion)));
  }
  const ::vk::ApplicationInfo application{
      .pApplicationName = "lghd", .pEngineName = "lgh shadow tracer", .apiVersion = kApiVersion};
  try {
    return {loader, ::vk::InstanceCreateInfo{.pApplicationInfo = &application}};
  } catch (const ::vk::SystemError& error) {
    throw Error(ErrorCode::Unavailable,
                fmt::format("vkCreateInstance failed: {} (no Vulkan driver installed?)",
                            resultName(static_cast<::vk::Result>(error.code().value()))));
  }
}

}  // namespace lgh::vk
