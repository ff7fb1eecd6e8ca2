// The Vulkan probe of /v1/info, run in a child process (`lghd --probe-vulkan`).
//
// Why a process: on the H100, creating a Vulkan instance inside lghd (on the render thread, and
// also on a thread of its own) made lghd abort in libepoxy, which then loaded GL; GL is now
// resolved per context (renderer/src/gl/gl_api.hpp), but the child process also keeps a driver
// that crashes or hangs out of the daemon's address space: it costs nothing but the report.
#pragma once

#include <sys/types.h>

#include <atomic>

#include "lgh/vulkan_info.hpp"

namespace lghd {

inline constexpr const char* kProbeVulkanFlag = "--probe-vulkan";

// The `lghd --probe-vulkan` mode: prints lgh::probeVulkan() as one JSON line; exit status 0.
int printVulkanProbe();

// Runs this executable with --probe-vulkan and parses what it prints. `child` holds the child's
// pid while it runs (0 otherwise), so that shutdown can kill a hung probe. Never throws: a failed
// child is reported in VulkanInfo::error.
lgh::VulkanInfo probeVulkanInChildProcess(std::atomic<pid_t>& child);

}  // namespace lghd
