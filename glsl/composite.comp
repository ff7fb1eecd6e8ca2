#version 450 core
// Composite pass (compute: see direct_lighting.comp for why): sums the lighting buffers into the
// final linear colour and puts the background (or transparency) where no geometry was drawn.
// The LGH lighting is unshadowed; the filtered shadow ratio scales it when the frame has one.
// Frames with direct lighting alone and no blended surfaces skip it: their direct lighting pass
// writes the output (LGH_FINAL_OUTPUT of direct_lighting.comp).
//
// It writes what the frame is read back as (include/frame_output.glsl: display codes for a PNG,
// linear light for an EXR, the rows turned over), or
//   LGH_SCENE_TARGET    frames with blended surfaces: linear light into the scene target, rows as
//                       GL stores them (the display pass turns them over after the forward blend)
// Output: image unit LGH_IMAGE_OUTPUT.
// Invocation groups of background pixels only store the background (include/skip_background.glsl).

#include "include/skip_background.glsl"
#include "include/slots.glsl"
#ifdef LGH_SCENE_TARGET
layout(binding = LGH_IMAGE_OUTPUT, rgba32f) writeonly uniform image2D uScene;
uniform int uHeight;
uniform vec4 uBackground;  // rgb, a = alpha of the background (0 when transparent)
#else
#include "include/frame_output.glsl"
#endif

layout(binding = 0) uniform sampler2D uDirect;
layout(binding = 1) uniform sampler2D uIndirect;
layout(binding = 2) uniform sampler2D uCoverage;  // G-buffer position: w = 1 where drawn
layout(binding = LGH_UNIT_COMPOSITE_RATIO) uniform sampler2D uShadowRatio;

uniform bool uHasIndirect;
uniform bool uHasShadowRatio;
uniform int uWidth;

layout(local_size_x = LGH_GROUP_2D, local_size_y = LGH_GROUP_2D) in;
#include "include/balanced_tiles.glsl"  // after the work-group size

// Where geometry was drawn.
vec4 linearColor(ivec2 pixel) {
  vec3 color = texelFetch(uDirect, pixel, 0).rgb;
  if (uHasIndirect) {
    float ratio = uHasShadowRatio ? texelFetch(uShadowRatio, pixel, 0).r : 1.0;
    color += texelFetch(uIndirect, pixel, 0).rgb * ratio;
  }
  return vec4(color, 1.0);
}

void main() {
  ivec2 pixel = balancedPixel();
  bool inFrame = pixel.x < uWidth && pixel.y < uHeight;
  bool covered = inFrame && texelFetch(uCoverage, pixel, 0).w >= 0.5;
#ifdef LGH_SCENE_TARGET
  if (inFrame) imageStore(uScene, pixel, covered ? linearColor(pixel) : uBackground);
#else
  if (!anyInvocationCovers(covered)) {
    if (inFrame) storeBackgroundUnlessCleared(outputTarget(pixel));
    return;
  }
  if (!inFrame) return;
  if (covered) {
    storeOutput(outputTarget(pixel), linearColor(pixel));
  } else {
    storeBackground(outputTarget(pixel));
  }
#endif
}
