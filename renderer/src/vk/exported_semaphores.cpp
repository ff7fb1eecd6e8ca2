#include "vk/exported_semaphores.hpp"

#include <unistd.h>

#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

constexpr auto kOpaqueFd = ::vk::ExternalSemaphoreHandleTypeFlagBits::eOpaqueFd;

::vk::raii::Semaphore createExportable(const ::vk::raii::Device& device) {
  const ::vk::ExportSemaphoreCreateInfo exportable{.handleTypes = kOpaqueFd};
  return {device, ::vk::SemaphoreCreateInfo{.pNext = &exportable}};
}

int exportFd(const ::vk::raii::Device& device, const ::vk::raii::Semaphore& semaphore) {
  return device.getSemaphoreFdKHR(
      ::vk::SemaphoreGetFdInfoKHR{.semaphore = *semaphore, .handleType = kOpaqueFd});
}

}  // namespace

ExportedSemaphores::ExportedSemaphores(const VulkanDevice& device)
    : device_(&device.device()),
      glDone_(createExportable(device.device())),
      vkDone_(createExportable(device.device())) {}

SemaphoreFds ExportedSemaphores::exportFds() const {
  SemaphoreFds fds;
  fds.glDone = exportFd(*device_, glDone_);
  try {
    fds.vkDone = exportFd(*device_, vkDone_);
  } catch (...) {
    close(fds.glDone);
    throw;
  }
  return fds;
}

}  // namespace lgh::vk
