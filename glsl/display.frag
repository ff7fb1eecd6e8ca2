#version 450 core
// Display pass (frames with blended surfaces): turns the linear scene target, composited and then
// blended over, into what the frame is read back as, with the rows turned over like the composite
// pass does for frames without blended surfaces:
//   LGH_DISPLAY_OUTPUT  PNG: exposure, tone map and sRGB as 8-bit codes (RGBA8UI target)
//   otherwise           EXR: linear light (RGBA16F or RGBA32F target)

#ifdef LGH_DISPLAY_OUTPUT
#include "include/display_transform.glsl"
#endif

layout(binding = 0) uniform sampler2D uScene;  // RGBA32F linear light, rows as GL stores them

uniform int uHeight;  // of the frame, to turn the rows over

#ifdef LGH_DISPLAY_OUTPUT
uniform int uToneMap;  // LGH_TONE_MAP_*
uniform float uExposure;
layout(location = 0) out uvec4 outCode;
#else
layout(location = 0) out vec4 outColor;
#endif

void main() {
  ivec2 pixel = ivec2(int(gl_FragCoord.x), uHeight - 1 - int(gl_FragCoord.y));
  vec4 color = texelFetch(uScene, pixel, 0);
#ifdef LGH_DISPLAY_OUTPUT
  outCode = uvec4(lghDisplayChannel(color.r, uToneMap, uExposure),
                  lghDisplayChannel(color.g, uToneMap, uExposure),
                  lghDisplayChannel(color.b, uToneMap, uExposure), lghAlpha8(color.a));
#else
  outColor = color;
#endif
}
