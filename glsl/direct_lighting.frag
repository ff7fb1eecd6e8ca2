#version 450 core
// Direct lighting pass: every analytic light of the scene evaluated with the glTF BRDF over the
// G-buffer, plus emission and a constant ambient term. Unshadowed until the Vulkan sidecar lands.
// Inputs: G-buffer (include/gbuffer.glsl), lights SSBO (binding 0). Output: HDR radiance.

#include "include/gbuffer.glsl"
#include "include/lights.glsl"

layout(std430, binding = 0) readonly buffer Lights { Light lights[]; };

uniform int uLightCount;
uniform vec3 uCameraPosition;
uniform float uAmbient;

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
  radiance += uAmbient * s.baseColor * s.occlusion;
  for (int i = 0; i < uLightCount; ++i) {
    vec3 toLight;
    vec3 incident = incidentLight(lights[i], s.position, toLight);
    radiance += incident * evaluateBrdfCosine(s, toViewer, toLight);
  }
  outRadiance = vec4(radiance, 1.0);
}
