// The Vulkan loader and instance for the shadow tracer: libvulkan.so.1 is opened at run time
// (vk::raii::Context) and never closed, and the instance asks for API 1.2 with no layers and no
// extensions (nothing is presented).
#pragma once

#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

// The process's loader, opened on first use. Throws lgh::Error(Unavailable) without one.
const ::vk::raii::Context& vulkanLoader();

// Throws lgh::Error(Unavailable) when the loader is older than 1.2 or no driver takes the
// instance.
::vk::raii::Instance createInstance();

}  // namespace lgh::vk
