#version 450 core
// Interleaved sampling, compositing (Lin & Yuksel 2019, Sec. 4.3): puts the full frame back
// together from the tile atlas that the raster or the compute path lit - the same code for both.
// Tile t of pixel p holds only tile t's lights, evaluated at p; the other tiles' lights are
// estimated from p's neighbours of those tiles within n - 1 pixels (1, 2 or 4 of them per tile):
// a tent of width n (bilinear interpolation of the tile's low-resolution image at p, so no n x n
// pattern appears) times how well their geometry matches p's (normals, distance from p's tangent
// plane: no light crosses depth edges), demodulated by their base colour (remodulated by p's), so
// that textures stay sharp. A tile with no matching neighbour is replaced by the mean of the
// others.
// This is the smoothing interleaving introduces; the error metrics report it.
// Inputs: tile atlas (unit 5), G-buffer (units 0..4). Output: indirect target (rgba16f).

#include "include/gbuffer.glsl"
#include "include/lgh_shading.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = LGH_UNIT_PASS_INPUT) uniform sampler2D uAtlas;
layout(rgba16f, binding = LGH_IMAGE_OUTPUT) uniform writeonly image2D uOutput;

uniform float uPixelFootprint;  // world size of one pixel at unit distance from the camera

const float kMinWeight = 1e-4;

vec3 reflectance(SurfacePoint s) { return max(s.baseColor, vec3(0.02)); }

// What the estimate needs of a neighbour, as readSurface() would give it, from three of the
// G-buffer's targets instead of every one: the pass reads (2n - 1)^2 neighbours per pixel.
struct Neighbour {
  vec3 position;
  vec3 normal;
  vec3 baseColor;
};

bool readNeighbour(ivec2 pixel, out Neighbour q) {
  vec4 position = texelFetch(gPosition, pixel, 0);
  if (position.w <= 0.5) return false;
  q = Neighbour(position.xyz, normalize(texelFetch(gNormal, pixel, 0).xyz),
                texelFetch(gAlbedo, pixel, 0).rgb);
  return true;
}

float geometryWeight(SurfacePoint p, Neighbour q, float planeSigma) {
  // cos^16 by squaring: pow() costs a logarithm and an exponential per neighbour.
  float facing = max(dot(p.normal, q.normal), 0.0);
  for (int i = 0; i < 4; ++i) facing *= facing;
  float planeDistance = dot(p.normal, q.position - p.position) / planeSigma;
  return facing * exp(-planeDistance * planeDistance);
}

// The first coordinate >= from that is congruent to residue mod n.
int firstOfResidue(int from, int residue) {
  return from + ((residue - from) % uInterleave + uInterleave) % uInterleave;
}

// Tile `tile`'s lighting at p, demodulated; false when no neighbour of that tile matches p.
bool tileEstimate(ivec2 pixel, SurfacePoint p, ivec2 tile, float planeSigma, out vec3 estimate) {
  int reach = uInterleave - 1;
  ivec2 first = ivec2(firstOfResidue(pixel.x - reach, tile.x), firstOfResidue(pixel.y - reach, tile.y));
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  for (int y = first.y; y <= pixel.y + reach; y += uInterleave) {
    for (int x = first.x; x <= pixel.x + reach; x += uInterleave) {
      ivec2 q = ivec2(x, y);
      Neighbour neighbour;
      if (!lghInFrame(q) || !readNeighbour(q, neighbour)) continue;
      vec2 tent = 1.0 - abs(vec2(q - pixel)) / float(uInterleave);
      float w = tent.x * tent.y * geometryWeight(p, neighbour, planeSigma);
      sum += w * texelFetch(uAtlas, lghAtlasPixel(q), 0).rgb / max(neighbour.baseColor, vec3(0.02));
      weightSum += w;
    }
  }
  estimate = weightSum > kMinWeight ? sum / weightSum : vec3(0.0);
  return weightSum > kMinWeight;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!lghInFrame(pixel)) return;
  SurfacePoint p;
  if (!readSurface(pixel, p)) {
    imageStore(uOutput, pixel, vec4(0.0));
    return;
  }
  float planeSigma =
      max(float(uInterleave) * uPixelFootprint * distance(p.position, uCameraPosition), 1e-6);
  vec3 total = vec3(0.0);
  int matched = 0;
  for (int ty = 0; ty < uInterleave; ++ty) {
    for (int tx = 0; tx < uInterleave; ++tx) {
      vec3 estimate;
      if (tileEstimate(pixel, p, ivec2(tx, ty), planeSigma, estimate)) {
        total += estimate;
        ++matched;
      }
    }
  }
  float tiles = float(uInterleave * uInterleave);
  vec3 radiance = matched > 0 ? total * (tiles / float(matched)) * reflectance(p) : vec3(0.0);
  imageStore(uOutput, pixel, vec4(radiance, 1.0));
}
