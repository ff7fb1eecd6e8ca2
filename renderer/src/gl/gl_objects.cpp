#include "gl/gl_objects.hpp"

namespace lgh::gl {

namespace detail {
std::array<std::atomic<std::int64_t>, kObjectKinds> gLiveObjects{};
}

std::array<std::int64_t, kObjectKinds> liveObjects() {
  std::array<std::int64_t, kObjectKinds> counts{};
  for (std::size_t i = 0; i < kObjectKinds; ++i) {
    counts[i] = detail::gLiveObjects[i].load(std::memory_order_relaxed);
  }
  return counts;
}

}  // namespace lgh::gl
