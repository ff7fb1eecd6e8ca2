#version 450 core
// Pixel packing: copies a frame's display codes (RGBA8UI, rows already in the image's order) into
// its pixel-pack buffer as tightly packed bytes, 3 per pixel (RGB) or 4 (RGBA). One invocation
// packs four consecutive pixels: 3 words (RGB) or 4 (RGBA), with one integer division for the
// first pixel's row (a vector division is a scalar loop per lane on a CPU rasterizer). A copy by
// glGetTextureImage that drops the alpha channel, or reads an integer format, is a slow
// conversion in some drivers; this is a plain buffer write.
// Input: the output target. Output: the pack buffer (word count rounded up; padding bytes are 0).

#include "include/slots.glsl"

layout(local_size_x = LGH_PACK_GROUP) in;

layout(binding = 0) uniform usampler2D uCodes;
layout(std430, binding = LGH_BIND_PACKED_PIXELS) writeonly buffer PackedPixels { uint words[]; };

uniform int uWidth;
uniform int uChannels;  // 3 or 4
uniform uint uWordCount;
uniform uint uPixelCount;

void store(uint word, uint value) {
  if (word < uWordCount) words[word] = value;
}

void main() {
  // Rows of work groups: one row holds at most GL_MAX_COMPUTE_WORK_GROUP_COUNT[0] of them.
  uint quad = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) +
              gl_GlobalInvocationID.x;
  uint first = quad * 4u;
  if (first >= uPixelCount) return;
  uint row = first / uint(uWidth);
  ivec2 texel = ivec2(int(first - row * uint(uWidth)), int(row));
  uvec4 c[4];
  for (int i = 0; i < 4; ++i) {
    c[i] = first + uint(i) < uPixelCount ? texelFetch(uCodes, texel, 0) & 0xFFu : uvec4(0u);
    texel.x += 1;
    if (texel.x == uWidth) texel = ivec2(0, texel.y + 1);
  }
  if (uChannels == 4) {
    for (int i = 0; i < 4; ++i) {
      store(first + uint(i), c[i].r | (c[i].g << 8) | (c[i].b << 16) | (c[i].a << 24));
    }
    return;
  }
  uint word = quad * 3u;
  store(word, c[0].r | (c[0].g << 8) | (c[0].b << 16) | (c[1].r << 24));
  store(word + 1u, c[1].g | (c[1].b << 8) | (c[2].r << 16) | (c[2].g << 24));
  store(word + 2u, c[2].b | (c[3].r << 8) | (c[3].g << 16) | (c[3].b << 24));
}
