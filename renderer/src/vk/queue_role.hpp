// Which of the tracer's Vulkan queues a submission goes to (vk/vulkan_device.hpp).
#pragma once

namespace lgh::vk {

// Which queue a submission goes to: the frames' (traces, and the builds and uploads of the render
// thread) or that of the builds made ahead on prefetch threads. The latter is the family's second
// queue where it has one, so that a build ahead waits for its own work only, not for the traces
// queued before it (which wait for GL's frames); else it is the frames' queue.
enum class QueueRole { Frames, BuildsAhead };

}  // namespace lgh::vk
