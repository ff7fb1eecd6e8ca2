// The interop semaphore pair of shadow_tracer.hpp: binary semaphores created exportable as
// opaque fds. GL signals `glDone` once the rays are written; the trace waits on it and signals
// `vkDone`, which GL waits on before it reads the visibility.
#pragma once

#include "vk/shadow_tracer.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

class ExportedSemaphores {
 public:
  explicit ExportedSemaphores(const VulkanDevice& device);

  // Fresh fds for both semaphores; the caller owns them (GL, once it imports them).
  SemaphoreFds exportFds() const;
  ::vk::Semaphore glDone() const { return *glDone_; }
  ::vk::Semaphore vkDone() const { return *vkDone_; }

 private:
  const ::vk::raii::Device* device_;
  ::vk::raii::Semaphore glDone_;
  ::vk::raii::Semaphore vkDone_;
};

}  // namespace lgh::vk
