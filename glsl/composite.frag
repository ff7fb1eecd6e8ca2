#version 450 core
// Composite pass: sums the lighting buffers into the final linear image and puts the background
// (or transparency) where no geometry was drawn. The LGH lighting is unshadowed; the filtered
// shadow ratio scales it when the frame has one. Tone mapping happens at encoding time, so EXR
// output stays linear.

#include "include/slots.glsl"

layout(binding = 0) uniform sampler2D uDirect;
layout(binding = 1) uniform sampler2D uIndirect;
layout(binding = 2) uniform sampler2D uCoverage;  // G-buffer position: w = 1 where drawn
layout(binding = LGH_UNIT_COMPOSITE_RATIO) uniform sampler2D uShadowRatio;

uniform bool uHasIndirect;
uniform bool uHasShadowRatio;
uniform vec4 uBackground;  // rgb, a = alpha of the background (0 when transparent)

layout(location = 0) out vec4 outColor;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  if (texelFetch(uCoverage, pixel, 0).w < 0.5) {
    outColor = uBackground;
    return;
  }
  vec3 color = texelFetch(uDirect, pixel, 0).rgb;
  if (uHasIndirect) {
    float ratio = uHasShadowRatio ? texelFetch(uShadowRatio, pixel, 0).r : 1.0;
    color += texelFetch(uIndirect, pixel, 0).rgb * ratio;
  }
  outColor = vec4(color, 1.0);
}
