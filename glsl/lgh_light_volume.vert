#version 450 core
// LGH raster lighting, light volumes: one instance per grid light of the levels below the top, a
// cube bounding the sphere of radius 2 r_l beyond which its blending weight is 0 (Lin & Yuksel
// 2019, Sec. 3.2). Instance i of interleave tile t draws light firstLight + t + i * n^2, so each
// light lands in exactly one tile. The clip-space tile transform maps the full frame's pixel
// centres onto the tile's pixel centres exactly (see LghRasterLightingPass::tileTransform).
// Inputs: grid lights, level table. Output: the light's index, flat.

// The program's defines are the fragment stage's: storage images are not for this stage.
#undef LGH_OVERDRAW
#include "include/lgh_shading.glsl"

uniform mat4 uViewProjection;
uniform vec4 uTileTransform;  // clip.xy = clip.xy * scale (xy) + offset (zw) * clip.w
uniform int uTile;

flat out uint vLight;

// 12 triangles, counter-clockwise seen from outside; corner bits: x = 1, y = 2, z = 4.
const int kCubeCorners[36] = int[36](4, 6, 2, 4, 2, 0, 1, 3, 7, 1, 7, 5, 1, 5, 4, 1, 4, 0, 2, 6, 7,
                                     2, 7, 3, 2, 3, 1, 2, 1, 0, 4, 5, 7, 4, 7, 6);

void main() {
  LghFrame frame = lghFrame();
  uint tiles = uint(uInterleave * uInterleave);
  uint index = lghFirstLight(frame) + uint(uTile) + uint(gl_InstanceID) * tiles;
  GridLight light = gridLights[index];
  float radius = lghInfluenceRadius(int(light.level), frame.topLevel, frame.alpha, frame.h1);
  int bits = kCubeCorners[gl_VertexID];
  vec3 corner = vec3(ivec3(bits, bits >> 1, bits >> 2) & 1) * 2.0 - 1.0;
  vec4 clip = uViewProjection * vec4(light.center + corner * radius, 1.0);
  clip.xy = clip.xy * uTileTransform.xy + uTileTransform.zw * clip.w;
  gl_Position = clip;
  vLight = index;
}
