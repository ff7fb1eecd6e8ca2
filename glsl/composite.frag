#version 450 core
// Composite pass: sums the lighting buffers into the final linear colour and puts the background
// (or transparency) where no geometry was drawn. The LGH lighting is unshadowed; the filtered
// shadow ratio scales it when the frame has one.
//
// It writes what the frame is read back as, with the rows turned over (the first row GL stores is
// the image's top row, so no one flips them on the CPU):
//   LGH_DISPLAY_OUTPUT  PNG: exposure, tone map and sRGB as 8-bit codes (RGBA8UI target)
//   otherwise           EXR: linear light (RGBA16F or RGBA32F target)
//   LGH_SCENE_TARGET    frames with blended surfaces: linear light into the scene target, rows as
//                       GL stores them (the display pass turns them over after the forward blend)

#include "include/slots.glsl"
#ifdef LGH_DISPLAY_OUTPUT
#include "include/display_transform.glsl"
#endif

layout(binding = 0) uniform sampler2D uDirect;
layout(binding = 1) uniform sampler2D uIndirect;
layout(binding = 2) uniform sampler2D uCoverage;  // G-buffer position: w = 1 where drawn
layout(binding = LGH_UNIT_COMPOSITE_RATIO) uniform sampler2D uShadowRatio;

uniform bool uHasIndirect;
uniform bool uHasShadowRatio;
uniform vec4 uBackground;  // rgb, a = alpha of the background (0 when transparent)
uniform int uHeight;       // of the frame, to turn the rows over

#ifdef LGH_DISPLAY_OUTPUT
uniform int uToneMap;  // LGH_TONE_MAP_*
uniform float uExposure;
layout(location = 0) out uvec4 outCode;
#else
layout(location = 0) out vec4 outColor;
#endif

vec4 linearColor(ivec2 pixel) {
  if (texelFetch(uCoverage, pixel, 0).w < 0.5) return uBackground;
  vec3 color = texelFetch(uDirect, pixel, 0).rgb;
  if (uHasIndirect) {
    float ratio = uHasShadowRatio ? texelFetch(uShadowRatio, pixel, 0).r : 1.0;
    color += texelFetch(uIndirect, pixel, 0).rgb * ratio;
  }
  return vec4(color, 1.0);
}

void main() {
#ifdef LGH_SCENE_TARGET
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#else
  ivec2 pixel = ivec2(int(gl_FragCoord.x), uHeight - 1 - int(gl_FragCoord.y));
#endif
  vec4 color = linearColor(pixel);
#ifdef LGH_DISPLAY_OUTPUT
  outCode = uvec4(lghDisplayChannel(color.r, uToneMap, uExposure),
                  lghDisplayChannel(color.g, uToneMap, uExposure),
                  lghDisplayChannel(color.b, uToneMap, uExposure), lghAlpha8(color.a));
#else
  outColor = color;
#endif
}
