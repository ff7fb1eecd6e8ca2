#version 460
// The ray met nothing.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require

#include "../include/hit_record.glsl"

layout(location = 0) rayPayloadInEXT HitRecord hitPayload;

void main() { hitPayload.t = -1.0; }
