#version 450 core
// Path-traced reference, first vertex: the pixel's G-buffer surface (the same points the LGH
// lights). Next-event estimation to the area lights only (the analytic lights' direct light is
// the frame's direct lighting, not part of what the LGH reproduces), and a bounce direction from
// the full BRDF (include/gi_brdf_sampling.glsl). docs/GI.md.

#include "include/gbuffer.glsl"
#include "include/gi_brdf_sampling.glsl"
#include "include/gi_camera_paths.glsl"
#include "include/gi_sources.glsl"

layout(local_size_x = 64) in;

uniform ivec2 uFrameSize;
uniform vec3 uCameraPosition;

void main() {
  uint path = cameraPathIndex();
  if (path >= uPathCount) return;
  uint pixelIndex = path / uSamples;
  ivec2 pixel = ivec2(int(pixelIndex % uint(uFrameSize.x)), int(pixelIndex / uint(uFrameSize.x)));
  GiCameraPath state;
  state.radiance = vec4(0.0);
  state.pending = vec4(0.0);
  SurfacePoint s;
  if (!readSurface(pixel, s)) {
    state.position = vec4(0.0);
    state.throughput = vec4(0.0);
    cameraPaths[path] = state;
    writeNoRay(path);
    return;
  }
  vec3 toViewer = normalize(uCameraPosition - s.position);
  uint seed = giPathSeed(uSeed, path);
  vec3 origin = s.position + s.normal * uSurfaceOffset;

  GiLightSample light = giSampleLight(s.position, giRandom(seed, 0u, 0u),
                                      vec2(giRandom(seed, 0u, 1u), giRandom(seed, 0u, 2u)));
  vec3 contribution =
      light.area ? evaluateBrdfCosine(s, toViewer, light.direction) * light.incident : vec3(0.0);
  if (!finite(contribution)) contribution = vec3(0.0);
  writeShadowRay(path, origin, light.direction, light.distance, contribution);

  vec3 l = giSampleBrdf(s, toViewer,
                        vec3(giRandom(seed, 0u, 3u), giRandom(seed, 0u, 4u), giRandom(seed, 0u, 5u)));
  float pdf = dot(l, l) > 0.0 ? giBrdfPdf(s, toViewer, l) : 0.0;
  vec3 weight = pdf > 0.0 ? evaluateBrdfCosine(s, toViewer, l) / pdf : vec3(0.0);
  if (!finite(weight)) weight = vec3(0.0);
  state.position = vec4(origin, any(greaterThan(weight, vec3(0.0))) ? 1.0 : 0.0);
  state.normal = vec4(s.normal, 0.0);
  state.throughput = vec4(weight, 0.0);
  state.pending = vec4(contribution, 0.0);
  state.next = vec4(l, 0.0);
  cameraPaths[path] = state;
}
