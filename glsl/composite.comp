#version 450 core
// Composite pass (compute: see direct_lighting.comp for why): sums the lighting buffers into the final linear colour and puts the background
// (or transparency) where no geometry was drawn. The LGH lighting is unshadowed; the filtered
// shadow ratio scales it when the frame has one.
//
// It writes what the frame is read back as, with the rows turned over (the first row GL stores is
// the image's top row, so no one flips them on the CPU):
//   LGH_DISPLAY_OUTPUT  PNG: exposure, tone map and sRGB as 8-bit codes (RGBA8UI target)
//   otherwise           EXR: linear light (LGH_OUTPUT_FORMAT: rgba16f or rgba32f target)
//   LGH_SCENE_TARGET    frames with blended surfaces: linear light into the scene target, rows as
//                       GL stores them (the display pass turns them over after the forward blend)
// Output: image unit LGH_IMAGE_OUTPUT.

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
uniform int uWidth;
uniform int uHeight;       // of the frame, to turn the rows over

layout(local_size_x = LGH_GROUP_2D, local_size_y = LGH_GROUP_2D) in;
#ifdef LGH_DISPLAY_OUTPUT
uniform int uToneMap;  // LGH_TONE_MAP_*
uniform float uExposure;
layout(binding = LGH_IMAGE_OUTPUT, rgba8ui) writeonly uniform uimage2D uCodes;
#else
layout(binding = LGH_IMAGE_OUTPUT, LGH_OUTPUT_FORMAT) writeonly uniform image2D uColor;
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
  ivec2 target = ivec2(gl_GlobalInvocationID.xy);
  if (target.x >= uWidth || target.y >= uHeight) return;
#ifdef LGH_SCENE_TARGET
  ivec2 pixel = target;
#else
  ivec2 pixel = ivec2(target.x, uHeight - 1 - target.y);
#endif
  vec4 color = linearColor(pixel);
#ifdef LGH_DISPLAY_OUTPUT
  imageStore(uCodes, target,
             uvec4(lghDisplayChannel(color.r, uToneMap, uExposure),
                   lghDisplayChannel(color.g, uToneMap, uExposure),
                   lghDisplayChannel(color.b, uToneMap, uExposure), lghAlpha8(color.a)));
#else
  imageStore(uColor, target, color);
#endif
}
