#version 450 core
// Interleaved sampling, split (Lin & Yuksel 2019, Sec. 4.3): the G-buffer rearranged into n x n
// low-resolution tiles - full-resolution pixel p goes to tile p mod n at p / n - so that a light
// drawn into one tile covers 1/n^2 of the pixels it would cover in the full frame. Drawn as one
// full-screen pass over the tile atlas; atlas pixels past the frame's edge get no coverage.
// The albedo target is sRGB like the G-buffer's (GL_FRAMEBUFFER_SRGB on), so the copy is exact.
// Inputs: G-buffer (units 0..3, 6), G-buffer depth (unit 5).
// Outputs: tile position, normal, albedo, material, layers, depth.

#include "include/gbuffer.glsl"
#include "include/lgh_shading.glsl"

layout(binding = LGH_UNIT_PASS_INPUT) uniform sampler2D uDepth;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outMaterial;
layout(location = 4) out uvec4 outLayers;

void main() {
  int tile;
  ivec2 pixel = lghFramePixel(ivec2(gl_FragCoord.xy), tile);
  if (!lghInFrame(pixel)) {
    outPosition = vec4(0.0);
    outNormal = vec4(0.0);
    outAlbedo = vec4(0.0);
    outMaterial = vec4(0.0);
    outLayers = uvec4(0u);
    gl_FragDepth = 1.0;
    return;
  }
  outPosition = texelFetch(gPosition, pixel, 0);
  outNormal = texelFetch(gNormal, pixel, 0);
  outAlbedo = texelFetch(gAlbedo, pixel, 0);
  outMaterial = texelFetch(gMaterial, pixel, 0);
  outLayers = texelFetch(gLayers, pixel, 0);
  gl_FragDepth = texelFetch(uDepth, pixel, 0).r;
}
