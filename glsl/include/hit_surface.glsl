// A ray hit resolved into the surface point it stands for: position, normals, base colour and
// diffuse albedo, from the scene's triangles as GL holds them for this (renderer/src/gi/
// hit_geometry.hpp, mirrored there) and the hit's instance, geometry, triangle and barycentrics
// (include/hit_record.glsl). The triangle indexing is the acceleration structures' own
// (vk::packGeometry), so every hit names the triangle it met.
#ifndef LGH_HIT_SURFACE_GLSL
#define LGH_HIT_SURFACE_GLSL

#include "include/gi_material.glsl"
#include "include/hit_record.glsl"
#include "include/slots.glsl"

struct HitVertex {  // 64 bytes: object space
  vec4 position;
  vec4 normal;
  vec4 uv;  // xy: TEXCOORD_0, zw: TEXCOORD_1
  vec4 color;
};
struct HitGeometry {  // 16 bytes: one primitive with triangles
  uint firstVertex;
  uint firstIndex;
  uint material;  // index into giMaterials (the default material is the last entry)
  uint triangleCount;
};
struct HitInstance {  // 144 bytes
  mat4 world;
  mat4 normalWorld;  // inverse transpose of world
  uvec4 geometries;  // x: its mesh's first geometry, y: their count, z: 1 mirrored (det < 0)
};

layout(std430, binding = LGH_BIND_GI_VERTICES) readonly buffer HitVertices {
  HitVertex hitVertices[];
};
layout(std430, binding = LGH_BIND_GI_INDICES) readonly buffer HitIndices { uint hitIndices[]; };
layout(std430, binding = LGH_BIND_GI_GEOMETRIES) readonly buffer HitGeometries {
  HitGeometry hitGeometries[];
};
layout(std430, binding = LGH_BIND_GI_INSTANCES) readonly buffer HitInstances {
  HitInstance hitInstances[];
};

struct HitSurface {
  vec3 position;         // world space, on the triangle
  vec3 geometricNormal;  // unit, facing where the ray came from
  vec3 normal;           // interpolated vertex normal, unit, on the geometric normal's side
  vec4 baseColor;
  vec3 albedo;           // diffuse albedo (include/gi_material.glsl)
  vec3 emission;
  // The ray met the back of a single-sided surface: glTF draws no back faces, and light that
  // reaches one is absorbed (else the sunlit top of a thin roof would light the room below
  // through it: a VPL lies on its surface, and a shadow ray ends just short of it).
  bool backFace;
};

// `direction`: the ray's direction (any length).
HitSurface resolveHit(HitRecord hit, vec3 direction) {
  HitInstance instance = hitInstances[hit.instance];
  HitGeometry geometry = hitGeometries[instance.geometries.x + hit.geometry];
  uint first = geometry.firstIndex + 3u * hit.primitive;
  HitVertex v0 = hitVertices[geometry.firstVertex + hitIndices[first]];
  HitVertex v1 = hitVertices[geometry.firstVertex + hitIndices[first + 1u]];
  HitVertex v2 = hitVertices[geometry.firstVertex + hitIndices[first + 2u]];
  vec3 b = vec3(1.0 - hit.barycentrics.x - hit.barycentrics.y, hit.barycentrics);

  HitSurface surface;
  vec3 p0 = (instance.world * vec4(v0.position.xyz, 1.0)).xyz;
  vec3 p1 = (instance.world * vec4(v1.position.xyz, 1.0)).xyz;
  vec3 p2 = (instance.world * vec4(v2.position.xyz, 1.0)).xyz;
  surface.position = b.x * p0 + b.y * p1 + b.z * p2;
  vec3 crossed = cross(p1 - p0, p2 - p0);
  vec3 ng = dot(crossed, crossed) > 0.0 ? normalize(crossed) : -normalize(direction);
  // glTF: counter-clockwise is the front, in world space; a mirroring transform swaps the sides.
  bool counterClockwiseSide = dot(ng, direction) < 0.0;
  bool front = counterClockwiseSide != (instance.geometries.z != 0u);
  if (dot(ng, direction) > 0.0) ng = -ng;
  vec3 objectNormal = b.x * v0.normal.xyz + b.y * v1.normal.xyz + b.z * v2.normal.xyz;
  vec3 n = mat3(instance.normalWorld) * objectNormal;
  n = dot(n, n) > 0.0 ? normalize(n) : ng;
  if (dot(n, ng) < 0.0) n = -n;
  surface.geometricNormal = ng;
  surface.normal = n;

  vec4 uv = b.x * v0.uv + b.y * v1.uv + b.z * v2.uv;
  vec4 color = b.x * v0.color + b.y * v1.color + b.z * v2.color;
  GiMaterial material = giMaterials[geometry.material];
  surface.backFace = !front && material.params.z == 0.0;
  surface.baseColor = giBaseColor(material, uv.xy, uv.zw, color);
  surface.albedo = giDiffuseAlbedo(material, surface.baseColor);
  surface.emission = material.emission.rgb;
  return surface;
}

#endif
