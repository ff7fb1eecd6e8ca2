#version 450 core
// Composite pass: sums the lighting buffers into the final linear image and puts the background
// (or transparency) where no geometry was drawn. Tone mapping happens at encoding time, so EXR
// output stays linear.

layout(binding = 0) uniform sampler2D uDirect;
layout(binding = 1) uniform sampler2D uIndirect;
layout(binding = 2) uniform sampler2D uCoverage;  // G-buffer position: w = 1 where drawn

uniform bool uHasIndirect;
uniform vec4 uBackground;  // rgb, a = alpha of the background (0 when transparent)

layout(location = 0) out vec4 outColor;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  if (texelFetch(uCoverage, pixel, 0).w < 0.5) {
    outColor = uBackground;
    return;
  }
  vec3 color = texelFetch(uDirect, pixel, 0).rgb;
  if (uHasIndirect) color += texelFetch(uIndirect, pixel, 0).rgb;
  outColor = vec4(color, 1.0);
}
