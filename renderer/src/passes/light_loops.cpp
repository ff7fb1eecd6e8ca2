#include "passes/light_loops.hpp"

#include <fmt/format.h>

namespace lgh {

std::string lightCountDefines(int lightCount) {
  if (lightCount < 0 || lightCount > kMaxUnrolledLights) return {};
  return fmt::format("#define LGH_LIGHT_COUNT {}\n", lightCount);
}

std::string shadowLayoutDefines(const ShadowRayLayout& layout) {
  if (layout.shadowedLights < 0 || layout.shadowedLights > kMaxUnrolledLights ||
      layout.lightSamples < 1 || layout.lightSamples > kMaxUnrolledLightSamples) {
    return {};
  }
  return fmt::format("#define LGH_SHADOWED_LIGHTS {}\n#define LGH_LIGHT_SAMPLES {}\n",
                     layout.shadowedLights, layout.lightSamples);
}

}  // namespace lgh
