// Normal generation for primitives whose asset leaves them out (or gives broken ones), and the
// small vector helpers the tangent code shares. Tangents come from MikkTSpace (mikktspace.hpp).
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

}  // namespace lgh
