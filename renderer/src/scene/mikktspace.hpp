// MikkTSpace tangents (Morten S. Mikkelsen, "Simulation of Wrinkled Surfaces Revisited", 2008, and
// the reference implementation's published algorithm), as glTF asks for where an asset has no
// TANGENT. Implemented here from that description, not vendored: no copy of mikktspace.c is
// packaged for Debian bookworm. Checked against the reference (the npm mikktspace package, a port
// of mikktspace.c) on a mirrored-UV mesh in tests/unit/test_mikktspace.cpp.
//
// The algorithm, with the reference's default settings (angular threshold 180 degrees):
//  1. Vertices are identified by value: corners with equal position, normal and texture
//     coordinate are one vertex, whatever their indices.
//  2. Per triangle: the normalised directions of dP/du and dP/dv, and whether the UV mapping
//     preserves orientation (the sign of the UV area). Triangles with no UV area or no extent
//     join any group; triangles that repeat a vertex are degenerate and set aside.
//  3. Per vertex, the triangles around it are grouped: a group grows across shared edges to
//     neighbours of the same UV orientation. Mirrored UV islands that meet at a vertex make two
//     groups, so the vertex gets two tangent frames.
//  4. A group's tangent: each triangle's dP/du projected into the vertex normal's plane and
//     normalised, weighted by the triangle's corner angle (in that plane), summed, normalised.
//     The bitangent sign is +1 for orientation-preserving groups, -1 otherwise.
//  5. Degenerate triangles copy the frame of another triangle at the same vertex.
// glTF's UV origin is the top-left of the image, MikkTSpace's the bottom-left: v is flipped
// before step 2, which gives what glTF exporters store (see tangents.hpp for the convention).
#pragma once

#include "scene/scene.hpp"

namespace lgh {

// Sets Vertex::tangent of every vertex from the UV set `uvSet` (0 or 1) and the (unit) vertex
// normals. Vertices whose corners get different frames (mirrored UV seams) are split, so the
// vertex count may grow; indices are rewritten to match. Never produces NaN.
void generateMikkTSpaceTangents(Primitive& primitive, int uvSet = 0);

}  // namespace lgh
