#version 460
// The shadow ray met nothing: visible.
#extension GL_EXT_ray_tracing : require

layout(location = 0) rayPayloadInEXT uint shadowRayMissed;

void main() { shadowRayMissed = 1u; }
