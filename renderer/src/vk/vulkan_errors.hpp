// Vulkan failures as lgh::Error: vk::raii reports a failed call by throwing vk::SystemError, and
// the tracer's public functions turn that into lgh::Error(Internal, "<step>: <call> failed:
// <VkResult name>") at their boundary, so nothing of Vulkan-Hpp escapes src/vk/.
#pragma once

#include <string>
#include <string_view>
#include <utility>

#include "lgh/error.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

// "VK_ERROR_DEVICE_LOST", as vulkan_core.h spells it.
std::string resultName(::vk::Result result);

// The lgh::Error for a failed Vulkan call: `step` names the tracer's step, `call` the call.
Error vulkanError(std::string_view step, std::string_view call, ::vk::Result result);

// Runs `body`; a vk::SystemError thrown inside comes out as vulkanError(step, ...), any other
// Vulkan-Hpp error as lgh::Error(Internal).
template <typename Body>
decltype(auto) translateVulkanErrors(std::string_view step, Body&& body) {
  try {
    return std::forward<Body>(body)();
  } catch (const ::vk::SystemError& error) {
    throw vulkanError(step, error.what(), static_cast<::vk::Result>(error.code().value()));
  } catch (const ::vk::LogicError& error) {  // Vulkan-Hpp's checks of its own arguments
    throw Error(ErrorCode::Internal, std::string(step) + ": " + error.what());
  }
}

}  // namespace lgh::vk
