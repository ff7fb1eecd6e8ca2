// The frame's output image and how a pixel's linear colour goes into it: display codes for a PNG
// (exposure, tone map and sRGB: include/display_transform.glsl) or linear light for an EXR
// (LGH_OUTPUT_FORMAT: rgba16f or rgba32f), with the rows turned over (the first row GL stores is
// the image's top row, so no one flips them on the CPU). Written by the composite pass, and by
// the direct lighting pass of frames that have nothing to composite (LGH_FINAL_OUTPUT).
// Image unit LGH_IMAGE_OUTPUT. On a CPU rasteriser the pass clears the image to the background
// before it runs (bindFrameOutput in composite_pass.cpp), so that invocation groups of background
// pixels store nothing: there an image store is a scalar loop over the SIMD lanes, while on a GPU
// the clear is the dearer of the two.
#ifndef LGH_FRAME_OUTPUT_GLSL
#define LGH_FRAME_OUTPUT_GLSL

#include "include/slots.glsl"
#ifdef LGH_DISPLAY_OUTPUT
#include "include/display_transform.glsl"
#endif

uniform int uHeight;       // of the frame, to turn the rows over
uniform vec4 uBackground;  // rgb, a = alpha of the background (0 when transparent)
uniform bool uBackgroundCleared;  // the output holds the background already
#ifdef LGH_DISPLAY_OUTPUT
uniform int uToneMap;  // LGH_TONE_MAP_*
uniform float uExposure;
// uBackground's display codes, as the CPU's display transform gives them: the same for every
// background pixel, so no pixel computes them (composite_pass.cpp).
uniform uvec4 uBackgroundCodes;
layout(binding = LGH_IMAGE_OUTPUT, rgba8ui) writeonly uniform uimage2D uCodes;
#else
layout(binding = LGH_IMAGE_OUTPUT, LGH_OUTPUT_FORMAT) writeonly uniform image2D uColor;
#endif

// Where the frame's `pixel` (GL's rows, bottom first) goes in the output.
ivec2 outputTarget(ivec2 pixel) { return ivec2(pixel.x, uHeight - 1 - pixel.y); }

void storeOutput(ivec2 target, vec4 color) {
#ifdef LGH_DISPLAY_OUTPUT
  imageStore(uCodes, target,
             uvec4(lghDisplayChannel(color.r, uToneMap, uExposure),
                   lghDisplayChannel(color.g, uToneMap, uExposure),
                   lghDisplayChannel(color.b, uToneMap, uExposure), lghAlpha8(color.a)));
#else
  imageStore(uColor, target, color);
#endif
}

// The background at `target`: uBackground, displayed.
void storeBackground(ivec2 target) {
#ifdef LGH_DISPLAY_OUTPUT
  imageStore(uCodes, target, uBackgroundCodes);
#else
  imageStore(uColor, target, uBackground);
#endif
}

// The background at `target` unless the output was cleared to it (for invocation groups of
// background pixels alone).
void storeBackgroundUnlessCleared(ivec2 target) {
  if (!uBackgroundCleared) storeBackground(target);
}

#endif
