#version 450 core
// Pixel packing: copies a frame's display codes (RGBA8UI, rows already in the image's order) into
// its pixel-pack buffer as tightly packed bytes, 3 per pixel (RGB) or 4 (RGBA), one 32-bit word
// per invocation. A copy by glGetTextureImage that drops the alpha channel, or reads an integer
// format, is a slow conversion in some drivers; this is a plain buffer write.
// Input: the output target. Output: the pack buffer (word count rounded up; padding bytes are 0).

#include "include/slots.glsl"

layout(local_size_x = LGH_PACK_GROUP) in;

layout(binding = 0) uniform usampler2D uCodes;
layout(std430, binding = LGH_BIND_PACKED_PIXELS) writeonly buffer PackedPixels { uint words[]; };

uniform int uWidth;
uniform int uChannels;  // 3 or 4
uniform uint uWordCount;
uniform uint uByteCount;

uint codeAt(uint byteIndex) {
  if (byteIndex >= uByteCount) return 0u;
  uint pixel = byteIndex / uint(uChannels);
  uint channel = byteIndex % uint(uChannels);
  ivec2 texel = ivec2(int(pixel % uint(uWidth)), int(pixel / uint(uWidth)));
  return texelFetch(uCodes, texel, 0)[channel] & 0xFFu;
}

void main() {
  // Rows of work groups: one row holds at most GL_MAX_COMPUTE_WORK_GROUP_COUNT[0] of them.
  uint word = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) +
              gl_GlobalInvocationID.x;
  if (word >= uWordCount) return;
  uint first = word * 4u;
  if (uChannels == 4) {
    if (first >= uByteCount) {
      words[word] = 0u;
      return;
    }
    uvec4 c = texelFetch(uCodes, ivec2(int(word % uint(uWidth)), int(word / uint(uWidth))), 0);
    words[word] = (c.r & 0xFFu) | ((c.g & 0xFFu) << 8) | ((c.b & 0xFFu) << 16) | ((c.a & 0xFFu) << 24);
    return;
  }
  words[word] = codeAt(first) | (codeAt(first + 1u) << 8) | (codeAt(first + 2u) << 16) |
                (codeAt(first + 3u) << 24);
}
