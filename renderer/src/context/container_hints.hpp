// What to fix when the GPU is not reachable, from what the machine shows: the NVIDIA container
// runtime's variables and the vendor files EGL and Vulkan look for. Appended to the errors of
// the context paths and of the shadow tracer; docs/TROUBLESHOOTING.md explains each.
#pragma once

#include <string>

namespace lgh {

// Hints for a missing EGL device ("" when nothing looks wrong).
std::string eglDeviceHints();
// Hints for a missing Vulkan driver ("" when nothing looks wrong).
std::string vulkanDriverHints();

}  // namespace lgh
