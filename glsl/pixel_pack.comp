#version 450 core
// Pixel packing on GPUs: copies a frame's display codes (RGBA8UI, rows already in the image's
// order) into its pixel-pack buffer as tightly packed bytes, 3 per pixel (RGB) or 4 (RGBA). A
// copy by glGetTextureImage that drops the alpha channel, or reads an integer format, is a slow
// conversion in NVIDIA's driver; this is a plain buffer write, one invocation per 32-bit word so
// that neighbouring invocations write neighbouring words, each finding its bytes' pixels by
// integer division. CPU rasterizers take the driver's copy (passes/pixel_pack_pass.hpp).
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

