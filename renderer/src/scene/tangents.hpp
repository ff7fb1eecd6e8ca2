// Normal and tangent generation for primitives whose asset leaves them out (or gives broken ones).
//
// Tangents are NOT full MikkTSpace: they are per-triangle UV-derivative tangents, accumulated per
// vertex weighted by the triangle's corner angle, Gram-Schmidt orthogonalised against the vertex
// normal. For the simple cases (planar or smoothly curved patches with non-mirrored, non-degenerate
// UVs) this matches MikkTSpace's result; at UV seams and mirrored islands that share vertices it
// can differ, because MikkTSpace splits such vertices and this does not.
//
// Conventions (glTF): tangent.xyz points along increasing u; the bitangent is
// cross(normal, tangent.xyz) * tangent.w and points along DEcreasing v, i.e. towards the top of the
// image, because glTF puts the UV origin at the image's top-left (this is what MikkTSpace yields
// when a glTF exporter feeds it flipped-v coordinates, and what normal maps expect: +Y = up).
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace lgh {

// A unit vector perpendicular to the unit vector `n` (any one).
glm::vec3 anyPerpendicular(const glm::vec3& n);

// True for a finite vector that is not (nearly) zero.
bool isUsableDirection(const glm::vec3& v);

// glTF's rule for a primitive without NORMAL: flat normals. Unwelds the primitive (each triangle
// gets its own three vertices) and gives every vertex its triangle's normal; degenerate triangles
// get an arbitrary unit normal.
void generateFlatNormals(Primitive& primitive);

// Replaces each vertex normal that is not usable (zero length, NaN, Inf) by the area-weighted
// average of the normals of the triangles using it, and normalises the usable ones. Returns how
// many vertices were repaired. A vertex on no non-degenerate triangle gets +Y.
std::size_t repairNormals(Primitive& primitive);

// Area-weighted smooth normals for every vertex (the repair above, applied to all vertices).
void generateSmoothNormals(Primitive& primitive);

// Tangents for every vertex from the UV set `uvSet` (0 or 1) and the vertex normals, which must
// already be unit length. Never produces NaN: a vertex whose UVs are degenerate gets
// anyPerpendicular(normal) with w = +1.
void generateTangents(Primitive& primitive, int uvSet = 0);

}  // namespace lgh
