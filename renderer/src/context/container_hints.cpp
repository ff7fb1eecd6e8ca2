#include "context/container_hints.hpp"

#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <string_view>

namespace lgh {
namespace {

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr ? value : "";
}

bool anyExists(std::initializer_list<const char*> paths) {
  std::error_code error;
  for (const char* path : paths) {
    if (std::filesystem::exists(path, error)) return true;
  }
  return false;
}

void append(std::string& hints, std::string_view hint) {
  hints += hints.empty() ? " (" : "; ";
  hints += hint;
}

void close(std::string& hints) {
  if (!hints.empty()) hints += ")";
}

// Under the NVIDIA container runtime, NVIDIA_DRIVER_CAPABILITIES decides which driver libraries
// are mounted: without "graphics" (or "all") there is no EGL and no Vulkan driver.
void checkCapabilities(std::string& hints) {
  const std::string visible = environment("NVIDIA_VISIBLE_DEVICES");
  const std::string capabilities = environment("NVIDIA_DRIVER_CAPABILITIES");
  if (visible.empty() || visible == "void") return;
  if (capabilities.find("graphics") == std::string::npos &&
      capabilities.find("all") == std::string::npos) {
    append(hints, "NVIDIA_DRIVER_CAPABILITIES is '" + capabilities +
                      "': it must include 'graphics' for EGL and Vulkan (e.g. "
                      "graphics,compute,utility)");
  }
}

}  // namespace

std::string eglDeviceHints() {
  std::string hints;
  checkCapabilities(hints);
  const bool nvidiaVisible = !environment("NVIDIA_VISIBLE_DEVICES").empty() ||
                             anyExists({"/dev/nvidiactl", "/proc/driver/nvidia/version"});
  const bool vendorFile = !environment("__EGL_VENDOR_LIBRARY_FILENAMES").empty() ||
                          anyExists({"/usr/share/glvnd/egl_vendor.d/10_nvidia.json",
                                     "/etc/glvnd/egl_vendor.d/10_nvidia.json"});
  if (nvidiaVisible && !vendorFile) {
    append(hints,
           "an NVIDIA GPU is present but glvnd finds no NVIDIA EGL vendor file: install "
           "10_nvidia.json in /usr/share/glvnd/egl_vendor.d (docker/nvidia/) or set "
           "__EGL_VENDOR_LIBRARY_FILENAMES");
  }
  close(hints);
  return hints;
}

std::string vulkanDriverHints() {
  std::string hints;
  checkCapabilities(hints);
  const bool icdFile = !environment("VK_DRIVER_FILES").empty() ||
                       !environment("VK_ICD_FILENAMES").empty() ||
                       anyExists({"/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d"});
  if (!icdFile) {
    append(hints,
           "no Vulkan ICD file found: NVIDIA's is nvidia_icd.json in /etc/vulkan/icd.d "
           "(docker/nvidia/), Mesa's come with mesa-vulkan-drivers; or set VK_DRIVER_FILES");
  }
  close(hints);
  return hints;
}

}  // namespace lgh
