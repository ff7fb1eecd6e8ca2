#version 450 core
// Pixel packing: copies a frame's display codes (RGBA8UI, rows already in the image's order) into
// its pixel-pack buffer as tightly packed bytes, 3 per pixel (RGB) or 4 (RGBA). A copy by
// glGetTextureImage that drops the alpha channel, or reads an integer format, is a slow
// conversion in some drivers; this is a plain buffer write. Two shapes of the same copy, chosen
// per device by measurement (docs/BENCHMARKS.md):
// - GPUs: one invocation per 32-bit word, so that neighbouring invocations write neighbouring
//   words; each finds its bytes' pixels by integer division.
// - CPU rasterizers (LGH_PACK_FOUR_PIXELS): one invocation packs four consecutive pixels, 3 words
//   (RGB) or 4 (RGBA), with one integer division for the first pixel's row: a vector division
//   is a scalar loop per lane there, and the per-word shape spent 16 of them per word.
// Input: the output target. Output: the pack buffer (word count rounded up; padding bytes are 0).

#include "include/slots.glsl"

layout(local_size_x = LGH_PACK_GROUP) in;

layout(binding = 0) uniform usampler2D uCodes;
layout(std430, binding = LGH_BIND_PACKED_PIXELS) writeonly buffer PackedPixels { uint words[]; };

uniform int uWidth;
uniform int uChannels;  // 3 or 4
uniform uint uWordCount;
uniform uint uPixelCount;

// Rows of work groups: one row holds at most GL_MAX_COMPUTE_WORK_GROUP_COUNT[0] of them.
uint invocationIndex() {
  return gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) +
         gl_GlobalInvocationID.x;
}

uint packCodes(uint first, uint second, uint third, uint fourth) {
  return first | (second << 8) | (third << 16) | (fourth << 24);
}

#ifdef LGH_PACK_FOUR_PIXELS

void store(uint word, uint value) {
  if (word < uWordCount) words[word] = value;
}

void main() {
  uint quad = invocationIndex();
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
    for (int i = 0; i < 4; ++i) store(first + uint(i), packCodes(c[i].r, c[i].g, c[i].b, c[i].a));
    return;
  }
  uint word = quad * 3u;
  store(word, packCodes(c[0].r, c[0].g, c[0].b, c[1].r));
  store(word + 1u, packCodes(c[1].g, c[1].b, c[2].r, c[2].g));
  store(word + 2u, packCodes(c[2].b, c[3].r, c[3].g, c[3].b));
}

#else

uint codeAt(uint byteIndex) {
  if (byteIndex >= uPixelCount * uint(uChannels)) return 0u;
  uint pixel = byteIndex / uint(uChannels);
  uint channel = byteIndex % uint(uChannels);
  ivec2 texel = ivec2(int(pixel % uint(uWidth)), int(pixel / uint(uWidth)));
  return texelFetch(uCodes, texel, 0)[channel] & 0xFFu;
}

void main() {
  uint word = invocationIndex();
  if (word >= uWordCount) return;
  uint first = word * 4u;
  if (uChannels == 4) {
    if (word >= uPixelCount) {
      words[word] = 0u;
      return;
    }
    uvec4 c = texelFetch(uCodes, ivec2(int(word % uint(uWidth)), int(word / uint(uWidth))), 0) &
              0xFFu;
    words[word] = packCodes(c.r, c.g, c.b, c.a);
    return;
  }
  words[word] = packCodes(codeAt(first), codeAt(first + 1u), codeAt(first + 2u), codeAt(first + 3u));
}

#endif
