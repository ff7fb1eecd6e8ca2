#include "scene/mikktspace.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "scene/tangents.hpp"

namespace lgh {
namespace {

constexpr int kNoNeighbour = -1;
constexpr int kNoGroup = -1;

bool notZero(float x) { return std::abs(x) > 1.17549435e-38F; }  // FLT_MIN, as the reference

glm::vec3 normalizedOrZero(const glm::vec3& v) {
  const float length = glm::length(v);
  return notZero(length) ? v / length : v;
}

struct TriangleInfo {
  std::array<int, 3> vertex{};  // welded vertex per corner
  std::array<int, 3> neighbour{kNoNeighbour, kNoNeighbour, kNoNeighbour};  // across edge i->i+1
  std::array<int, 3> group{kNoGroup, kNoGroup, kNoGroup};
  glm::vec3 os{0.0F};  // normalised dP/du (zero when undefined)
  glm::vec3 ot{0.0F};  // normalised dP/dv
  bool orientPreserving = false;
  bool groupWithAny = true;  // no UV area or no extent: joins any group
  bool degenerate = false;   // repeats a vertex
};

struct Group {
  int vertex = 0;  // the welded vertex the group is about
  bool orientPreserving = false;
  std::vector<int> triangles;
};

struct CornerFrame {
  glm::vec3 tangent{1.0F, 0.0F, 0.0F};
  float sign = 1.0F;
};

class MikkTSpace {
 public:
  MikkTSpace(const Primitive& primitive, int uvSet) : primitive_(primitive), uvSet_(uvSet) {}

  // The frame of every corner (index i of primitive.indices).
  std::vector<CornerFrame> run() {
    weldVertices();
    initTriangles();
    buildNeighbours();
    buildGroups();
    std::vector<CornerFrame> corners(primitive_.indices.size());
    evaluateGroups(corners);
    copyToDegenerateTriangles(corners);
    return corners;
  }

 private:
  const Vertex& cornerVertex(std::size_t triangle, int corner) const {
    return primitive_.vertices[primitive_.indices[triangle * 3 + static_cast<std::size_t>(corner)]];
  }

  // MikkTSpace's UV convention: origin bottom-left (glTF's v flipped).
  glm::vec2 uv(const Vertex& vertex) const {
    const glm::vec2 value = uvSet_ == 1 ? vertex.uv1 : vertex.uv0;
    return {value.x, 1.0F - value.y};
  }

  // A corner's position, normal and texture coordinate, bit for bit: corners weld when equal.
  using Key = std::array<std::uint32_t, 8>;
  static std::uint64_t hashOf(const Key& key) {
    std::uint64_t hash = 1469598103934665603ULL;
    for (const std::uint32_t word : key) hash = (hash ^ word) * 1099511628211ULL;
    return hash ^ (hash >> 32U);
  }

  Key keyOf(std::size_t triangle, int corner) const {
    const Vertex& v = cornerVertex(triangle, corner);
    const glm::vec2 texcoord = uv(v);
    const std::array<float, 8> values{v.position.x, v.position.y, v.position.z, v.normal.x,
                                      v.normal.y,   v.normal.z,   texcoord.x,   texcoord.y};
    Key key{};
    std::memcpy(key.data(), values.data(), sizeof(key));
    return key;
  }

  // Welded vertices are numbered in the order their first corners come. An open-addressing table
  // of welded vertices (linear probing, at most half full) rather than a node per corner.
  void weldVertices() {
    const std::size_t triangles = primitive_.indices.size() / 3;
    infos_.resize(triangles);
    welded_.clear();
    std::vector<Key> keys;
    const std::size_t slotCount = std::bit_ceil(std::max<std::size_t>(16, triangles * 6));
    const std::size_t mask = slotCount - 1;
    std::vector<int> slots(slotCount, -1);
    for (std::size_t t = 0; t < triangles; ++t) {
      for (int i = 0; i < 3; ++i) {
        const Key key = keyOf(t, i);
        std::size_t slot = static_cast<std::size_t>(hashOf(key)) & mask;
        while (slots[slot] >= 0 && keys[static_cast<std::size_t>(slots[slot])] != key) {
          slot = (slot + 1) & mask;
        }
        if (slots[slot] < 0) {
          slots[slot] = static_cast<int>(welded_.size());
          keys.push_back(key);
          welded_.push_back(primitive_.indices[t * 3 + static_cast<std::size_t>(i)]);
        }
        infos_[t].vertex[static_cast<std::size_t>(i)] = slots[slot];
      }
    }
  }

  void initTriangles() {
    for (std::size_t t = 0; t < infos_.size(); ++t) {
      TriangleInfo& info = infos_[t];
      info.degenerate = info.vertex[0] == info.vertex[1] || info.vertex[1] == info.vertex[2] ||
                        info.vertex[0] == info.vertex[2];
      if (info.degenerate) continue;
      const glm::vec3 p1 = cornerVertex(t, 0).position;
      const glm::vec3 p2 = cornerVertex(t, 1).position;
      const glm::vec3 p3 = cornerVertex(t, 2).position;
      const glm::vec2 t1 = uv(cornerVertex(t, 0));
      const glm::vec2 t2 = uv(cornerVertex(t, 1));
      const glm::vec2 t3 = uv(cornerVertex(t, 2));
      const float t21x = t2.x - t1.x;
      const float t21y = t2.y - t1.y;
      const float t31x = t3.x - t1.x;
      const float t31y = t3.y - t1.y;
      const glm::vec3 d1 = p2 - p1;
      const glm::vec3 d2 = p3 - p1;
      const float signedArea = t21x * t31y - t21y * t31x;
      const glm::vec3 os = t31y * d1 - t21y * d2;   // dP/du times the signed area
      const glm::vec3 ot = -t31x * d1 + t21x * d2;  // dP/dv times the signed area
      info.orientPreserving = signedArea > 0.0F;
      if (!notZero(signedArea)) continue;
      const float absArea = std::abs(signedArea);
      const float lengthOs = glm::length(os);
      const float lengthOt = glm::length(ot);
      const float s = info.orientPreserving ? 1.0F : -1.0F;
      if (notZero(lengthOs)) info.os = (s / lengthOs) * os;
      if (notZero(lengthOt)) info.ot = (s / lengthOt) * ot;
      if (notZero(lengthOs / absArea) && notZero(lengthOt / absArea)) info.groupWithAny = false;
    }
  }

  // Neighbours share an edge in opposite directions (consistent winding), as the reference's.
  // Where several triangles share a directed edge (a non-manifold mesh), the first of them counts.
  // The edges are listed by their first welded vertex (counting sort), so that finding (to, from)
  // looks through the few edges leaving `to`.
  void buildNeighbours() {
    struct Edge {
      int to;
      int triangle;
    };
    std::vector<int> start(welded_.size() + 1, 0);
    for (const TriangleInfo& info : infos_) {
      if (info.degenerate) continue;
      for (const int from : info.vertex) ++start[static_cast<std::size_t>(from) + 1];
    }
    for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
    std::vector<Edge> edges(static_cast<std::size_t>(start.back()));
    std::vector<int> filled(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < infos_.size(); ++t) {
      if (infos_[t].degenerate) continue;
      for (std::size_t e = 0; e < 3; ++e) {
        const auto from = static_cast<std::size_t>(infos_[t].vertex[e]);
        edges[static_cast<std::size_t>(filled[from]++)] = {infos_[t].vertex[(e + 1) % 3],
                                                           static_cast<int>(t)};
      }
    }
    for (std::size_t t = 0; t < infos_.size(); ++t) {
      if (infos_[t].degenerate) continue;
      for (std::size_t e = 0; e < 3; ++e) {
        const int from = infos_[t].vertex[e];
        const auto to = static_cast<std::size_t>(infos_[t].vertex[(e + 1) % 3]);
        const auto first = edges.begin() + start[to];
        const auto last = edges.begin() + start[to + 1];
        const auto back =
            std::find_if(first, last, [&](const Edge& edge) { return edge.to == from; });
        if (back != last && back->triangle != static_cast<int>(t)) {
          infos_[t].neighbour[e] = back->triangle;
        }
      }
    }
  }

  int cornerOf(const TriangleInfo& info, int vertex) const {
    for (int i = 0; i < 3; ++i) {
      if (info.vertex[static_cast<std::size_t>(i)] == vertex) return i;
    }
    return -1;
  }

  // Grows group `g` into triangle `t` around the group's vertex, and on to its neighbours there.
  // Iterative (an explicit stack): a large fan would recurse deeply.
  void assign(int start, int g) {
    std::vector<int> pending{start};
    while (!pending.empty()) {
      const int t = pending.back();
      pending.pop_back();
      if (t < 0) continue;
      TriangleInfo& info = infos_[static_cast<std::size_t>(t)];
      Group& group = groups_[static_cast<std::size_t>(g)];
      const int i = cornerOf(info, group.vertex);
      if (i < 0) continue;
      auto& assigned = info.group[static_cast<std::size_t>(i)];
      if (assigned != kNoGroup) continue;
      if (info.groupWithAny && info.group[0] == kNoGroup && info.group[1] == kNoGroup &&
          info.group[2] == kNoGroup) {
        info.orientPreserving = group.orientPreserving;
      }
      if (info.orientPreserving != group.orientPreserving) continue;
      assigned = g;
      group.triangles.push_back(t);
      pending.push_back(info.neighbour[static_cast<std::size_t>(i > 0 ? i - 1 : 2)]);
      pending.push_back(info.neighbour[static_cast<std::size_t>(i)]);
    }
  }

  void buildGroups() {
    for (std::size_t t = 0; t < infos_.size(); ++t) {
      TriangleInfo& info = infos_[t];
      if (info.degenerate || info.groupWithAny) continue;
      for (int i = 0; i < 3; ++i) {
        if (info.group[static_cast<std::size_t>(i)] != kNoGroup) continue;
        Group group;
        group.vertex = info.vertex[static_cast<std::size_t>(i)];
        group.orientPreserving = info.orientPreserving;
        groups_.push_back(group);
        assign(static_cast<int>(t), static_cast<int>(groups_.size()) - 1);
      }
    }
  }

  // The corner angle at corner i of triangle t, measured in the plane of normal n.
  float cornerAngle(std::size_t t, int i, const glm::vec3& n) const {
    const glm::vec3 p0 = cornerVertex(t, i > 0 ? i - 1 : 2).position;
    const glm::vec3 p1 = cornerVertex(t, i).position;
    const glm::vec3 p2 = cornerVertex(t, i < 2 ? i + 1 : 0).position;
    glm::vec3 v1 = p0 - p1;
    glm::vec3 v2 = p2 - p1;
    v1 = normalizedOrZero(v1 - n * glm::dot(n, v1));
    v2 = normalizedOrZero(v2 - n * glm::dot(n, v2));
    return std::acos(std::clamp(glm::dot(v1, v2), -1.0F, 1.0F));
  }

  void evaluateGroups(std::vector<CornerFrame>& corners) const {
    for (const Group& group : groups_) {
      glm::vec3 sum(0.0F);
      for (int t : group.triangles) {
        const TriangleInfo& info = infos_[static_cast<std::size_t>(t)];
        const int i = cornerOf(info, group.vertex);
        const glm::vec3 n = cornerVertex(static_cast<std::size_t>(t), i).normal;
        const glm::vec3 os = normalizedOrZero(info.os - n * glm::dot(n, info.os));
        sum += cornerAngle(static_cast<std::size_t>(t), i, n) * os;
      }
      CornerFrame frame;
      frame.tangent = normalizedOrZero(sum);
      frame.sign = group.orientPreserving ? 1.0F : -1.0F;
      for (int t : group.triangles) {
        const int i = cornerOf(infos_[static_cast<std::size_t>(t)], group.vertex);
        corners[static_cast<std::size_t>(t) * 3 + static_cast<std::size_t>(i)] = frame;
      }
    }
  }

  // A degenerate triangle's corner takes the frame of a non-degenerate corner of the same vertex.
  void copyToDegenerateTriangles(std::vector<CornerFrame>& corners) const {
    if (std::none_of(infos_.begin(), infos_.end(),
                     [](const TriangleInfo& info) { return info.degenerate; })) {
      return;
    }
    constexpr std::size_t kNone = ~std::size_t{0};
    std::vector<std::size_t> firstCorner(welded_.size(), kNone);
    for (std::size_t t = 0; t < infos_.size(); ++t) {
      if (infos_[t].degenerate) continue;
      for (std::size_t i = 0; i < 3; ++i) {
        std::size_t& first = firstCorner[static_cast<std::size_t>(infos_[t].vertex[i])];
        if (first == kNone) first = t * 3 + i;
      }
    }
    for (std::size_t t = 0; t < infos_.size(); ++t) {
      if (!infos_[t].degenerate) continue;
      for (std::size_t i = 0; i < 3; ++i) {
        const std::size_t first = firstCorner[static_cast<std::size_t>(infos_[t].vertex[i])];
        if (first != kNone) corners[t * 3 + i] = corners[first];
      }
    }
  }

  const Primitive& primitive_;
  int uvSet_;
  std::vector<TriangleInfo> infos_;
  std::vector<std::uint32_t> welded_;  // welded vertex -> a representative index
  std::vector<Group> groups_;
};

// A tangent the shaders can use: orthogonal to n, unit, finite.
glm::vec4 finishFrame(const CornerFrame& frame, const glm::vec3& normal) {
  // Without UV area (a mesh without texture coordinates) the accumulated direction may lie along
  // the normal: keep only its part in the tangent plane.
  glm::vec3 t = frame.tangent - normal * glm::dot(normal, frame.tangent);
  if (!isUsableDirection(t)) t = anyPerpendicular(normal);
  return glm::vec4(glm::normalize(t), frame.sign);
}

}  // namespace

void generateMikkTSpaceTangents(Primitive& primitive, int uvSet) {
  primitive.indices.resize(primitive.indices.size() - primitive.indices.size() % 3);
  const std::vector<CornerFrame> corners = MikkTSpace(primitive, uvSet).run();
  // Give each corner its frame; a vertex whose corners disagree is split. New vertices are
  // numbered in the order their corners come; the copies of one vertex are chained (`next`).
  constexpr std::uint32_t kNone = ~std::uint32_t{0};
  std::vector<Vertex> vertices;
  vertices.reserve(primitive.vertices.size());
  std::vector<std::uint32_t> firstCopy(primitive.vertices.size(), kNone);
  std::vector<std::uint32_t> nextCopy;
  nextCopy.reserve(primitive.vertices.size());
  for (std::size_t c = 0; c < primitive.indices.size(); ++c) {
    const std::uint32_t index = primitive.indices[c];
    const glm::vec4 tangent = finishFrame(corners[c], primitive.vertices[index].normal);
    std::uint32_t* link = &firstCopy[index];
    while (*link != kNone && vertices[*link].tangent != tangent) link = &nextCopy[*link];
    if (*link == kNone) {
      *link = static_cast<std::uint32_t>(vertices.size());
      vertices.push_back(primitive.vertices[index]);
      vertices.back().tangent = tangent;
      nextCopy.push_back(kNone);
    }
    primitive.indices[c] = *link;
  }
  // Vertices no triangle uses keep a valid frame too.
  for (std::size_t v = 0; v < primitive.vertices.size(); ++v) {
    if (firstCopy[v] != kNone) continue;
    Vertex vertex = primitive.vertices[v];
    vertex.tangent = glm::vec4(anyPerpendicular(vertex.normal), 1.0F);
    vertices.push_back(vertex);
  }
  primitive.vertices = std::move(vertices);
}

}  // namespace lgh
