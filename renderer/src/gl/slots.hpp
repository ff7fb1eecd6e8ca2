// The binding and work-group slots of glsl/include/slots.glsl, for C++: the same #defines, so the
// passes bind where the shaders look.
#pragma once

#include "include/slots.glsl"

namespace lgh::gl {

// Work groups of LGH_GROUP_2D x LGH_GROUP_2D invocations covering `pixels` along one axis.
constexpr unsigned groups2D(int pixels) {
  return static_cast<unsigned>((pixels + LGH_GROUP_2D - 1) / LGH_GROUP_2D);
}

}  // namespace lgh::gl
