#version 450 core
// One pass of the edge-avoiding a-trous wavelet filter (Dammertz et al. 2010) over the shadow
// ratio: a 5x5 B3-spline kernel with holes (taps uStep pixels apart; the step doubles every pass),
// weighted by how alike the surfaces are: normals (cosine to a power) and the distance of the tap
// from the pixel's tangent plane, relative to the pixel's footprint. No weight on the ratio
// itself: the noise is what is to be removed. Pixels without geometry neither give nor take.
// Inputs: ratio (sampler), G-buffer position and normal. Output: ratio (image).

#include "include/gbuffer.glsl"
#include "include/slots.glsl"

layout(local_size_x = LGH_GROUP_2D, local_size_y = LGH_GROUP_2D) in;

layout(binding = LGH_UNIT_PASS_INPUT) uniform sampler2D uRatioIn;
layout(r16f, binding = LGH_IMAGE_SHADOW_RATIO) uniform writeonly image2D uRatioOut;

uniform ivec2 uFrameSize;
uniform int uStep;
uniform vec3 uCameraPosition;
uniform vec2 uFootprint;        // a pixel's world size at distance d: d * x + y (perspective: x,
                                // orthographic: y)
uniform float uPlaneSigma;      // tolerance of the plane distance, in footprints per step

const float KERNEL[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);

// The normal weight, cos^64: the sharpness of the normals' edge stop, by squaring (pow() costs a
// logarithm and an exponential per tap).
float normalWeight(vec3 normal, vec3 tapNormal) {
  float c = max(dot(normal, tapNormal), 0.0);
  for (int i = 0; i < 6; ++i) c *= c;
  return c;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, uFrameSize))) return;
  vec4 position = texelFetch(gPosition, pixel, 0);
  float center = texelFetch(uRatioIn, pixel, 0).r;
  if (position.w < 0.5) {
    imageStore(uRatioOut, pixel, vec4(center));
    return;
  }
  vec3 normal = normalize(texelFetch(gNormal, pixel, 0).xyz);
  float footprint =
      max(distance(position.xyz, uCameraPosition) * uFootprint.x + uFootprint.y, 1e-6);
  float planeScale = 1.0 / (uPlaneSigma * footprint * float(uStep));
  float sum = 0.0;
  float weights = 0.0;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      ivec2 tap = pixel + ivec2(dx, dy) * uStep;
      if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, uFrameSize))) continue;
      vec4 tapPosition = texelFetch(gPosition, tap, 0);
      if (tapPosition.w < 0.5) continue;
      vec3 tapNormal = normalize(texelFetch(gNormal, tap, 0).xyz);
      float planeDistance = abs(dot(normal, tapPosition.xyz - position.xyz)) * planeScale;
      float weight = KERNEL[abs(dx)] * KERNEL[abs(dy)] * normalWeight(normal, tapNormal) *
                     exp(-planeDistance);
      sum += weight * texelFetch(uRatioIn, tap, 0).r;
      weights += weight;
    }
  }
  imageStore(uRatioOut, pixel, vec4(weights > 0.0 ? sum / weights : center));
}
