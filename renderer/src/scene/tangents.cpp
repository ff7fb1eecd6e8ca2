#include "scene/tangents.hpp"

#include <cmath>

namespace lgh {
namespace {

// Squared length below which a direction is treated as zero. Positions are in metres; 1e-24
// (a 1e-12 long vector) is far below anything a real asset uses as a meaningful direction.
constexpr float kTinySquared = 1e-24F;

struct Triangle {
  std::uint32_t index[3];
};

// Calls `visit(Triangle)` for each triangle whose indices are all valid.
template <typename Visit>
void forEachTriangle(const Primitive& primitive, Visit&& visit) {
  const std::size_t vertexCount = primitive.vertices.size();
  for (std::size_t i = 0; i + 2 < primitive.indices.size(); i += 3) {
    Triangle triangle{{primitive.indices[i], primitive.indices[i + 1], primitive.indices[i + 2]}};
    if (triangle.index[0] < vertexCount && triangle.index[1] < vertexCount &&
        triangle.index[2] < vertexCount) {
      visit(triangle);
    }
  }
}

// Twice the triangle's area times its unit normal (counter-clockwise front face, as glTF).
glm::vec3 areaNormal(const Primitive& primitive, const Triangle& triangle) {
  const glm::vec3& p0 = primitive.vertices[triangle.index[0]].position;
  const glm::vec3& p1 = primitive.vertices[triangle.index[1]].position;
  const glm::vec3& p2 = primitive.vertices[triangle.index[2]].position;
  return glm::cross(p1 - p0, p2 - p0);
}

}  // namespace

bool isUsableDirection(const glm::vec3& v) {
  const float lengthSquared = glm::dot(v, v);
  return std::isfinite(lengthSquared) && lengthSquared > kTinySquared;
}

glm::vec3 anyPerpendicular(const glm::vec3& n) {
  if (!isUsableDirection(n)) return glm::vec3(1.0F, 0.0F, 0.0F);
  const glm::vec3 unit = glm::normalize(n);
  // Gram-Schmidt on the coordinate axis least aligned with n: X unless n is close to X.
  const glm::vec3 axis = std::abs(unit.x) < 0.9F ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(axis - unit * glm::dot(unit, axis));
}

void generateFlatNormals(Primitive& primitive) {
  std::vector<Vertex> vertices;
  vertices.reserve(primitive.indices.size());
  forEachTriangle(primitive, [&](const Triangle& triangle) {
    const glm::vec3 n = areaNormal(primitive, triangle);
    const glm::vec3 normal = isUsableDirection(n) ? glm::normalize(n) : glm::vec3(0, 1, 0);
    for (std::uint32_t index : triangle.index) {
      Vertex vertex = primitive.vertices[index];
      vertex.normal = normal;
      vertices.push_back(vertex);
    }
  });
  primitive.indices.resize(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    primitive.indices[i] = static_cast<std::uint32_t>(i);
  }
  primitive.vertices = std::move(vertices);
}

std::size_t repairNormals(Primitive& primitive) {
  std::vector<glm::vec3> sums(primitive.vertices.size(), glm::vec3(0.0F));
  forEachTriangle(primitive, [&](const Triangle& triangle) {
    const glm::vec3 n = areaNormal(primitive, triangle);  // length = 2 * area: area weighting
    if (!isUsableDirection(n)) return;
    for (std::uint32_t index : triangle.index) sums[index] += n;
  });
  std::size_t repaired = 0;
  for (std::size_t i = 0; i < primitive.vertices.size(); ++i) {
    glm::vec3& normal = primitive.vertices[i].normal;
    if (isUsableDirection(normal)) {
      normal = glm::normalize(normal);
      continue;
    }
    normal = isUsableDirection(sums[i]) ? glm::normalize(sums[i]) : glm::vec3(0, 1, 0);
    ++repaired;
  }
  return repaired;
}

void generateSmoothNormals(Primitive& primitive) {
  for (Vertex& vertex : primitive.vertices) vertex.normal = glm::vec3(0.0F);
  repairNormals(primitive);
}

}  // namespace lgh
