#version 450 core
// Direct lighting pass: the lecture's illumination equation over the G-buffer,
//   emission + global ambient x ambient material
//   + sum over the analytic lights of (ambient part + visibility x (diffuse + specular part))
// with each material model's lobes (include/light_terms.glsl, include/brdf.glsl). Per-light
// ambient is never shadowed; the diffuse and specular parts are scaled by the shadow rays'
// visibility (1 for lights without) and by relief mapping's self-shadowing.
// Gouraud and flat surfaces bring the diffuse + specular sum evaluated per vertex or per
// primitive; their pixels scale it by the ratio of their shadowed to their unshadowed per-pixel
// sum (the ratio estimator the LGH's shadows use too), so that shadows keep the pixel's detail.
// Inputs: G-buffer (include/gbuffer.glsl), lights SSBO, shadow-ray visibility bits.
// Output: HDR radiance (image unit LGH_IMAGE_OUTPUT); with LGH_FINAL_OUTPUT, for frames with
// nothing to composite (no LGH lighting, no blended surfaces), the frame's output itself, as the
// composite pass would write it (include/frame_output.glsl): one full-screen pass less, which a
// CPU rasteriser feels (docs/BENCHMARKS.md).
// A compute pass, not a fullscreen triangle: on GPUs with few graphics units (Hopper) a fragment
// pass runs on a small part of the chip. Compiled for the frame's material models and layers
// (LGH_BRDF_MODELS / LGH_BRDF_LAYERS of include/brdf.glsl), as the LGH kernels are.
// Invocation groups of background pixels only store the background (include/skip_background.glsl).

#include "include/skip_background.glsl"
#define LGH_READ_VISIBILITY
#define LGH_LIGHTS_BUFFER
#include "include/gbuffer.glsl"
#include "include/light_terms.glsl"
#include "include/ray_batch.glsl"

#ifdef LGH_FINAL_OUTPUT
#include "include/frame_output.glsl"
#else
layout(binding = LGH_IMAGE_OUTPUT, rgba16f) writeonly uniform image2D uRadiance;
#endif

layout(local_size_x = LGH_GROUP_2D, local_size_y = LGH_GROUP_2D) in;
// The dispatch covers the tiles from uFirstTile on: all of them, or where the output was cleared
// before, those that can show a surface (passes/surface_tiles.hpp).
uniform uvec2 uFirstTile;
#define LGH_FIRST_TILE uFirstTile
#include "include/balanced_tiles.glsl"  // after the work-group size

#ifdef LGH_LIGHT_COUNT  // compiled for the frame's lights: the loop over them unrolls
#define uLightCount LGH_LIGHT_COUNT
#else
uniform int uLightCount;
#endif
uniform vec3 uCameraPosition;
uniform float uAmbient;
uniform bool uHasEmission;  // else the G-buffer pass left the emissive target unwritten
uniform int uFrameWidth;
uniform int uFrameHeight;

// Relief mapping hides light i where bit i of the pixel's mask is set (first 23 lights).
float selfShadowVisibility(SurfacePoint s, int light) {
  return light < 23 && (s.selfShadowMask & (1u << uint(light))) != 0u ? 0.0 : 1.0;
}

// Alpha 0 where nothing was drawn (the final output: the background there).
vec4 directRadiance(ivec2 pixel) {
  SurfacePoint s;
  if (!readSurface(pixel, s)) return vec4(0.0);
  vec3 toViewer = normalize(uCameraPosition - s.position);
  vec3 radiance = uHasEmission ? texelFetch(gEmissive, pixel, 0).rgb : vec3(0.0);
  radiance += uAmbient * ambientResponse(s);
  uint pixelIndex = uint(pixel.y) * uint(uFrameWidth) + uint(pixel.x);
  vec3 shadowed = vec3(0.0);
  vec3 unshadowed = vec3(0.0);
  for (int i = 0; i < uLightCount; ++i) {
    LightTerms terms = lightTerms(lights[i], s, toViewer);
    radiance += terms.ambient;
    unshadowed += terms.direct;
    if (any(greaterThan(terms.direct, vec3(0.0)))) {
      shadowed += terms.direct * directLightVisibility(pixelIndex, i) * selfShadowVisibility(s, i);
    }
  }
  if (s.hasVertexLit) {
    float total = luminance(unshadowed);
    radiance += s.vertexLit * (total > 0.0 ? luminance(shadowed) / total : 1.0);
  } else {
    radiance += shadowed;
  }
  return vec4(radiance, 1.0);
}

void storeRadiance(ivec2 pixel, vec4 radiance) {
#ifdef LGH_FINAL_OUTPUT
  // Full float: the composite reads the radiance rounded to half floats, so a code may differ
  // by one step from a composited frame's.
  if (radiance.a > 0.5) {
    storeOutput(outputTarget(pixel), radiance);
  } else {
    storeBackground(outputTarget(pixel));
  }
#else
  imageStore(uRadiance, pixel, radiance);
#endif
}

void main() {
  ivec2 pixel = balancedPixel();
  bool inFrame = pixel.x < uFrameWidth && pixel.y < uFrameHeight;
  if (!anyInvocationCovers(inFrame && surfaceCovered(pixel))) {
#ifdef LGH_FINAL_OUTPUT
    if (inFrame) storeBackgroundUnlessCleared(outputTarget(pixel));
#else
    if (inFrame) storeRadiance(pixel, vec4(0.0));
#endif
    return;
  }
  if (inFrame) storeRadiance(pixel, directRadiance(pixel));
}
