#version 450 core
// Direct lighting pass: every analytic light of the scene evaluated with the glTF BRDF over the
// G-buffer, times its visibility from the shadow rays (1 for lights without), plus emission and a
// constant ambient term.
// Inputs: G-buffer (include/gbuffer.glsl), lights SSBO, shadow-ray visibility bits.
// Output: HDR radiance.

#define LGH_READ_VISIBILITY
#include "include/gbuffer.glsl"
#include "include/lights.glsl"
#include "include/ray_batch.glsl"

layout(std430, binding = LGH_BIND_LIGHTS) readonly buffer Lights { Light lights[]; };

uniform int uLightCount;
uniform vec3 uCameraPosition;
uniform float uAmbient;
uniform int uFrameWidth;

layout(location = 0) out vec4 outRadiance;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  SurfacePoint s;
  if (!readSurface(pixel, s)) {
    outRadiance = vec4(0.0);
    return;
  }
  vec3 toViewer = normalize(uCameraPosition - s.position);
  vec3 radiance = texelFetch(gEmissive, pixel, 0).rgb;
  radiance += uAmbient * ambientResponse(s);
  uint pixelIndex = uint(pixel.y) * uint(uFrameWidth) + uint(pixel.x);
  for (int i = 0; i < uLightCount; ++i) {
    vec3 toLight;
    vec3 incident = incidentLight(lights[i], s.position, toLight);
    vec3 reflected = incident * evaluateBrdfCosine(s, toViewer, toLight);
    if (any(greaterThan(reflected, vec3(0.0)))) reflected *= directLightVisibility(pixelIndex, i);
    radiance += reflected;
  }
  outRadiance = vec4(radiance, 1.0);
}
