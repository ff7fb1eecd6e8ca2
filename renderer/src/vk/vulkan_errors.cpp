#include "vk/vulkan_errors.hpp"

#include <array>
#include <utility>

#include <fmt/format.h>

namespace lgh::vk {
namespace {

#define LGH_VK_RESULT(name) std::pair<VkResult, const char*>(name, #name)
constexpr std::array kResultNames = {
    LGH_VK_RESULT(VK_SUCCESS),
    LGH_VK_RESULT(VK_NOT_READY),
    LGH_VK_RESULT(VK_TIMEOUT),
    LGH_VK_RESULT(VK_EVENT_SET),
    LGH_VK_RESULT(VK_EVENT_RESET),
    LGH_VK_RESULT(VK_INCOMPLETE),
    LGH_VK_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY),
    LGH_VK_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY),
    LGH_VK_RESULT(VK_ERROR_INITIALIZATION_FAILED),
    LGH_VK_RESULT(VK_ERROR_DEVICE_LOST),
    LGH_VK_RESULT(VK_ERROR_MEMORY_MAP_FAILED),
    LGH_VK_RESULT(VK_ERROR_LAYER_NOT_PRESENT),
    LGH_VK_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT),
    LGH_VK_RESULT(VK_ERROR_FEATURE_NOT_PRESENT),
    LGH_VK_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER),
    LGH_VK_RESULT(VK_ERROR_TOO_MANY_OBJECTS),
    LGH_VK_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED),
    LGH_VK_RESULT(VK_ERROR_FRAGMENTED_POOL),
    LGH_VK_RESULT(VK_ERROR_UNKNOWN),
    LGH_VK_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY),
    LGH_VK_RESULT(VK_ERROR_INVALID_EXTERNAL_HANDLE),
    LGH_VK_RESULT(VK_ERROR_FRAGMENTATION),
    LGH_VK_RESULT(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS),
    LGH_VK_RESULT(VK_PIPELINE_COMPILE_REQUIRED),
    LGH_VK_RESULT(VK_ERROR_VALIDATION_FAILED_EXT),
    LGH_VK_RESULT(VK_ERROR_NOT_PERMITTED_KHR),
    LGH_VK_RESULT(VK_THREAD_IDLE_KHR),
    LGH_VK_RESULT(VK_THREAD_DONE_KHR),
    LGH_VK_RESULT(VK_OPERATION_DEFERRED_KHR),
    LGH_VK_RESULT(VK_OPERATION_NOT_DEFERRED_KHR),
    LGH_VK_RESULT(VK_ERROR_COMPRESSION_EXHAUSTED_EXT),
};
#undef LGH_VK_RESULT

// vk::SystemError::what() is "<call>: <the result as Vulkan-Hpp spells it>"; keep the call.
std::string_view callOnly(std::string_view message) {
  const auto colon = message.rfind(": ");
  return colon == std::string_view::npos ? message : message.substr(0, colon);
}

}  // namespace

std::string resultName(::vk::Result result) {
  for (const auto& [value, name] : kResultNames) {
    if (value == static_cast<VkResult>(result)) return name;
  }
  return fmt::format("VkResult {}", static_cast<int>(result));
}

Error vulkanError(std::string_view step, std::string_view call, ::vk::Result result) {
  std::string message = fmt::format("{}: {} failed: {}", step, callOnly(call), resultName(result));
  if (result == ::vk::Result::eErrorDeviceLost) {
    message += " (the Vulkan device is lost: the shadow tracer must be created again)";
  }
  return Error(ErrorCode::Internal, std::move(message));
}

}  // namespace lgh::vk
