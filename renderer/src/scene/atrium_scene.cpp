#include "scene/atrium_scene.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace lgh {
namespace {

enum AtriumMaterial { kFloor, kPlaster, kMarble, kStone, kCeiling, kRed, kBlue, kGreen, kMetal };

constexpr float kHalfWidth = 6.0F;
constexpr float kHalfLength = 20.0F;
constexpr float kHeight = 10.0F;
constexpr float kColonnadeX = 3.5F;
constexpr float kColumnRadius = 0.35F;
constexpr float kColumnHeight = 7.0F;
constexpr float kColumnSpacing = 4.0F;
constexpr int kColumnsPerRow = 9;
constexpr float kSkylightHalfWidth = 1.6F;

Vertex vertexAt(const glm::vec3& position, const glm::vec3& normal, const glm::vec3& tangent,
                const glm::vec2& uv) {
  Vertex vertex;
  vertex.position = position;
  vertex.normal = normal;
  vertex.tangent = glm::vec4(tangent, 1.0F);
  vertex.uv0 = uv;
  vertex.uv1 = uv;
  return vertex;
}

// A flat rectangle from `corner` along `u` and `v` (its normal is cross(u, v): counter-clockwise
// seen from the front), split into nu x nv quads; texture coordinates in metres / uvScale.
void addGrid(Primitive& primitive, const glm::vec3& corner, const glm::vec3& u, const glm::vec3& v,
             int nu, int nv, float uvScale) {
  const glm::vec3 normal = glm::normalize(glm::cross(u, v));
  const glm::vec3 tangent = glm::normalize(u);
  const auto base = static_cast<std::uint32_t>(primitive.vertices.size());
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      const float s = static_cast<float>(i) / static_cast<float>(nu);
      const float t = static_cast<float>(j) / static_cast<float>(nv);
      const glm::vec2 uv(s * glm::length(u) / uvScale, t * glm::length(v) / uvScale);
      primitive.vertices.push_back(vertexAt(corner + s * u + t * v, normal, tangent, uv));
    }
  }
  const auto stride = static_cast<std::uint32_t>(nu + 1);
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const std::uint32_t a =
          base + static_cast<std::uint32_t>(j) * stride + static_cast<std::uint32_t>(i);
      primitive.indices.insert(primitive.indices.end(),
                               {a, a + 1, a + stride + 1, a, a + stride + 1, a + stride});
    }
  }
}

// An axis-aligned box from `low` to `high`, outward faces.
void addBox(Primitive& primitive, const glm::vec3& low, const glm::vec3& high) {
  const glm::vec3 d = high - low;
  const glm::vec3 x(d.x, 0, 0), y(0, d.y, 0), z(0, 0, d.z);
  addGrid(primitive, low, z, y, 1, 1, 1.0F);      // -X
  addGrid(primitive, low + x, y, z, 1, 1, 1.0F);  // +X
  addGrid(primitive, low, x, z, 1, 1, 1.0F);      // -Y
  addGrid(primitive, low + y, z, x, 1, 1, 1.0F);  // +Y
  addGrid(primitive, low, y, x, 1, 1, 1.0F);      // -Z
  addGrid(primitive, low + z, x, y, 1, 1, 1.0F);  // +Z
}

// A cylinder about the Y axis from y0 to y1, outward normals, open at both ends.
void addCylinder(Primitive& primitive, const glm::vec3& base, float radius, float height,
                 int segments, int rings) {
  const auto first = static_cast<std::uint32_t>(primitive.vertices.size());
  for (int ring = 0; ring <= rings; ++ring) {
    const float t = static_cast<float>(ring) / static_cast<float>(rings);
    for (int segment = 0; segment <= segments; ++segment) {
      const float phi =
          glm::two_pi<float>() * static_cast<float>(segment) / static_cast<float>(segments);
      const glm::vec3 normal(std::cos(phi), 0.0F, std::sin(phi));
      primitive.vertices.push_back(vertexAt(
          base + glm::vec3(0.0F, t * height, 0.0F) + radius * normal, normal,
          glm::vec3(-normal.z, 0.0F, normal.x),
          glm::vec2(static_cast<float>(segment) / static_cast<float>(segments), t * height)));
    }
  }
  const auto stride = static_cast<std::uint32_t>(segments + 1);
  for (int ring = 0; ring < rings; ++ring) {
    for (int segment = 0; segment < segments; ++segment) {
      const std::uint32_t a =
          first + static_cast<std::uint32_t>(ring) * stride + static_cast<std::uint32_t>(segment);
      primitive.indices.insert(primitive.indices.end(),
                               {a, a + stride, a + stride + 1, a, a + stride + 1, a + 1});
    }
  }
}

// The stone between two columns at x = `x`, from z0 to z1: a semicircular arch springing at
// kColumnHeight, filled up to the ceiling (the clerestory wall), `depth` thick along X. Made of
// the two faces (x - depth/2, x + depth/2), the curved soffit and nothing else: the ends meet the
// neighbouring arches.
void addArchBay(Primitive& primitive, float x, float z0, float z1, float depth, int segments) {
  const float centreZ = 0.5F * (z0 + z1);
  const float radius = 0.5F * (z1 - z0) - kColumnRadius;
  const float spring = kColumnHeight;
  for (const float side : {-1.0F, 1.0F}) {
    const float faceX = x + side * 0.5F * depth;
    const glm::vec3 normal(side, 0.0F, 0.0F);
    const auto first = static_cast<std::uint32_t>(primitive.vertices.size());
    for (int s = 0; s <= segments; ++s) {
      const float angle = glm::pi<float>() * static_cast<float>(s) / static_cast<float>(segments);
      const float z = centreZ - radius * std::cos(angle);
      const float y = spring + radius * std::sin(angle);
      // The arc point, and the point on the ceiling above it.
      primitive.vertices.push_back(vertexAt({faceX, y, z}, normal, {0, 0, 1}, {z, y}));
      primitive.vertices.push_back(vertexAt({faceX, kHeight, z}, normal, {0, 0, 1}, {z, kHeight}));
    }
    // The strips beside the arch down to the springing, over the column's width.
    for (const float edge : {z0, z1}) {
      const float inner = edge == z0 ? z0 + kColumnRadius : z1 - kColumnRadius;
      const glm::vec3 a(faceX, spring, std::min(edge, inner));
      const glm::vec3 u(0.0F, 0.0F, std::fabs(inner - edge));
      const glm::vec3 v(0.0F, kHeight - spring, 0.0F);
      if (side > 0.0F) {
        addGrid(primitive, a, v, u, 4, 1, 1.0F);  // normal +X
      } else {
        addGrid(primitive, a, u, v, 1, 4, 1.0F);  // normal -X
      }
    }
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t a = first + 2 * static_cast<std::uint32_t>(s);
      // Vertex 2s is on the arc, 2s + 1 on the ceiling above it.
      if (side > 0.0F) {
        primitive.indices.insert(primitive.indices.end(), {a, a + 1, a + 3, a, a + 3, a + 2});
      } else {
        primitive.indices.insert(primitive.indices.end(), {a, a + 3, a + 1, a, a + 2, a + 3});
      }
    }
  }
  // The soffit: the underside of the arch, facing its centre.
  const auto first = static_cast<std::uint32_t>(primitive.vertices.size());
  for (int s = 0; s <= segments; ++s) {
    const float angle = glm::pi<float>() * static_cast<float>(s) / static_cast<float>(segments);
    const glm::vec3 normal(0.0F, -std::sin(angle), std::cos(angle));
    const float z = centreZ - radius * std::cos(angle);
    const float y = spring + radius * std::sin(angle);
    for (const float side : {-1.0F, 1.0F}) {
      primitive.vertices.push_back(
          vertexAt({x + side * 0.5F * depth, y, z}, normal, {1, 0, 0}, {side, angle}));
    }
  }
  for (int s = 0; s < segments; ++s) {
    const std::uint32_t a = first + 2 * static_cast<std::uint32_t>(s);
    primitive.indices.insert(primitive.indices.end(), {a, a + 1, a + 3, a, a + 3, a + 2});
  }
}

// A cloth hanging from a bar at `top` (its centre), `width` along X and `length` down, draped in
// vertical folds that deepen towards the hem and sway along Z; nu x nv quads, one-sided geometry
// (its material is double-sided).
void addCloth(Primitive& primitive, const glm::vec3& top, float width, float length, int nu, int nv,
              float phase) {
  const auto first = static_cast<std::uint32_t>(primitive.vertices.size());
  const auto at = [&](float s, float t) {
    const float folds = 0.18F * (0.3F + t) * std::sin(7.0F * glm::pi<float>() * s + phase);
    const float sway = 0.35F * t * t * std::sin(2.0F * phase + 1.3F * s);
    const float gather = 1.0F - 0.12F * t * std::sin(glm::pi<float>() * s);
    return top + glm::vec3((s - 0.5F) * width * gather, -t * length, folds + sway);
  };
  constexpr float kStep = 1e-3F;
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      const float s = static_cast<float>(i) / static_cast<float>(nu);
      const float t = static_cast<float>(j) / static_cast<float>(nv);
      const glm::vec3 p = at(s, t);
      const glm::vec3 ds = at(s + kStep, t) - at(s - kStep, t);
      const glm::vec3 dt = at(s, t + kStep) - at(s, t - kStep);
      const glm::vec3 normal = glm::normalize(glm::cross(ds, dt));
      primitive.vertices.push_back(vertexAt(p, normal, glm::normalize(ds), {s, t}));
    }
  }
  const auto stride = static_cast<std::uint32_t>(nu + 1);
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const std::uint32_t a =
          first + static_cast<std::uint32_t>(j) * stride + static_cast<std::uint32_t>(i);
      primitive.indices.insert(primitive.indices.end(),
                               {a, a + 1, a + stride + 1, a, a + stride + 1, a + stride});
    }
  }
}

Primitive surface(int material) {
  Primitive primitive;
  primitive.material = material;
  return primitive;
}

// Floor, walls, ceiling: facing into the hall.
Mesh makeShell() {
  const float w = kHalfWidth;
  const float l = kHalfLength;
  const float h = kHeight;
  Primitive floor = surface(kFloor);
  addGrid(floor, {-w, 0, l}, {2 * w, 0, 0}, {0, 0, -2 * l}, 24, 80, 2.0F);
  Primitive walls = surface(kPlaster);
  addGrid(walls, {-w, 0, l}, {0, 0, -2 * l}, {0, h, 0}, 40, 10, 2.0F);  // left, facing +X
  addGrid(walls, {w, 0, -l}, {0, 0, 2 * l}, {0, h, 0}, 40, 10, 2.0F);   // right, facing -X
  addGrid(walls, {-w, 0, -l}, {2 * w, 0, 0}, {0, h, 0}, 12, 10, 2.0F);  // far end, facing +Z
  addGrid(walls, {w, 0, l}, {-2 * w, 0, 0}, {0, h, 0}, 12, 10, 2.0F);   // near end, facing -Z
  Primitive ceiling = surface(kCeiling);
  const float s = kSkylightHalfWidth;
  addGrid(ceiling, {-w, h, l}, {0, 0, -2 * l}, {w - s, 0, 0}, 40, 4, 2.0F);  // facing down
  addGrid(ceiling, {s, h, l}, {0, 0, -2 * l}, {w - s, 0, 0}, 40, 4, 2.0F);
  return Mesh{"atrium_shell", {floor, walls, ceiling}};
}

Mesh makeColumn() {
  Primitive marble = surface(kMarble);
  addCylinder(marble, {0, 0.5F, 0}, kColumnRadius, kColumnHeight - 0.8F, 64, 24);
  Primitive stone = surface(kStone);
  const float p = kColumnRadius + 0.12F;
  addBox(stone, {-p, 0.0F, -p}, {p, 0.5F, p});                           // plinth
  addBox(stone, {-p, kColumnHeight - 0.3F, -p}, {p, kColumnHeight, p});  // abacus
  return Mesh{"column", {marble, stone}};
}

Mesh makeArcades() {
  Primitive stone = surface(kStone);
  for (const float x : {-kColonnadeX, kColonnadeX}) {
    for (int bay = 0; bay + 1 < kColumnsPerRow; ++bay) {
      const float z0 = -16.0F + kColumnSpacing * static_cast<float>(bay);
      addArchBay(stone, x, z0, z0 + kColumnSpacing, 0.7F, 96);
    }
  }
  return Mesh{"arcades", {stone}};
}

Mesh makeCloths() {
  Mesh mesh{"cloths", {}};
  const int colors[3] = {kRed, kBlue, kGreen};
  const float x[3] = {0.0F, 1.6F, -1.6F};
  const float z[3] = {-10.0F, -2.0F, 6.0F};
  for (int k = 0; k < 3; ++k) {
    Primitive cloth = surface(colors[k]);
    addCloth(cloth, {x[k], 8.6F, z[k]}, 2.4F, 5.2F, 72, 132, 0.9F * static_cast<float>(k));
    mesh.primitives.push_back(std::move(cloth));
  }
  // The bars the cloths hang from, across the nave between the colonnades.
  Primitive bars = surface(kMetal);
  for (int k = 0; k < 3; ++k) {
    addBox(bars, {-kColonnadeX, 8.58F, z[k] - 0.04F}, {kColonnadeX, 8.66F, z[k] + 0.04F});
  }
  mesh.primitives.push_back(std::move(bars));
  return mesh;
}

// Polished rails along the colonnades at handrail height, finely tessellated tubes.
Mesh makeRails() {
  Primitive metal = surface(kMetal);
  for (const float x : {-kColonnadeX + 0.9F, kColonnadeX - 0.9F}) {
    const auto first = static_cast<std::uint32_t>(metal.vertices.size());
    constexpr int kSegments = 32;
    constexpr int kRings = 160;
    constexpr float kRadius = 0.06F;
    for (int ring = 0; ring <= kRings; ++ring) {
      const float z =
          -kHalfLength + 1.0F +
          (2.0F * kHalfLength - 2.0F) * static_cast<float>(ring) / static_cast<float>(kRings);
      for (int s = 0; s <= kSegments; ++s) {
        const float phi =
            glm::two_pi<float>() * static_cast<float>(s) / static_cast<float>(kSegments);
        const glm::vec3 normal(std::cos(phi), std::sin(phi), 0.0F);
        metal.vertices.push_back(vertexAt(glm::vec3(x, 1.0F, z) + kRadius * normal, normal,
                                          {0, 0, 1}, {static_cast<float>(s), z}));
      }
    }
    const auto stride = static_cast<std::uint32_t>(kSegments + 1);
    for (int ring = 0; ring < kRings; ++ring) {
      for (int s = 0; s < kSegments; ++s) {
        const std::uint32_t a =
            first + static_cast<std::uint32_t>(ring) * stride + static_cast<std::uint32_t>(s);
        metal.indices.insert(metal.indices.end(),
                             {a, a + 1, a + stride + 1, a, a + stride + 1, a + stride});
      }
    }
  }
  return Mesh{"rails", {metal}};
}

// 256 x 256 sRGB floor tiles: 4 x 4 stone slabs of two tones with grout lines and a faint mottle.
Image8 makeFloorTexture() {
  constexpr int kSize = 256;
  constexpr int kTile = kSize / 4;
  Image8 image;
  image.width = kSize;
  image.height = kSize;
  image.channels = 4;
  image.pixels.resize(static_cast<std::size_t>(kSize) * kSize * 4);
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const bool grout = x % kTile < 2 || y % kTile < 2;
      const bool dark = ((x / kTile) + (y / kTile)) % 2 == 1;
      const int mottle = static_cast<int>(((x * 73 + y * 151) ^ (x * y)) % 13) - 6;
      int r = dark ? 150 : 205;
      int g = dark ? 132 : 190;
      int b = dark ? 112 : 165;
      if (grout) r = g = b = 95;
      std::uint8_t* p = &image.pixels[(static_cast<std::size_t>(y) * kSize + x) * 4];
      p[0] = static_cast<std::uint8_t>(std::clamp(r + mottle, 0, 255));
      p[1] = static_cast<std::uint8_t>(std::clamp(g + mottle, 0, 255));
      p[2] = static_cast<std::uint8_t>(std::clamp(b + mottle, 0, 255));
      p[3] = 255;
    }
  }
  return image;
}

Material material(const std::string& name, const glm::vec3& color, float roughness,
                  float metallic = 0.0F) {
  Material m;
  m.name = name;
  m.baseColorFactor = glm::vec4(color, 1.0F);
  m.metallicFactor = metallic;
  m.roughnessFactor = roughness;
  return m;
}

std::vector<Material> makeMaterials() {
  std::vector<Material> materials(kMetal + 1);
  materials[kFloor] = material("floor_tiles", glm::vec3(1.0F), 0.7F);
  materials[kFloor].baseColorTexture.image = 0;
  materials[kPlaster] = material("plaster", {0.78F, 0.74F, 0.66F}, 0.9F);
  materials[kMarble] = material("marble", {0.85F, 0.83F, 0.80F}, 0.35F);
  materials[kStone] = material("stone", {0.62F, 0.56F, 0.48F}, 0.85F);
  materials[kCeiling] = material("timber", {0.42F, 0.30F, 0.20F}, 0.8F);
  materials[kRed] = material("cloth_red", {0.70F, 0.08F, 0.06F}, 0.95F);
  materials[kBlue] = material("cloth_blue", {0.08F, 0.16F, 0.60F}, 0.95F);
  materials[kGreen] = material("cloth_green", {0.10F, 0.50F, 0.12F}, 0.95F);
  for (int cloth : {kRed, kBlue, kGreen}) {
    materials[static_cast<std::size_t>(cloth)].doubleSided = true;
  }
  materials[kMetal] = material("polished_brass", {0.95F, 0.80F, 0.55F}, 0.25F, 1.0F);
  return materials;
}

LightDesc light(LightType type, const glm::vec3& position, const glm::vec3& direction,
                const glm::vec3& color, float intensity) {
  const glm::vec3 d = glm::normalize(direction);
  LightDesc desc;
  desc.type = type;
  desc.position = {position.x, position.y, position.z};
  desc.direction = {d.x, d.y, d.z};
  desc.color = {color.x, color.y, color.z};
  desc.intensity = intensity;
  desc.attenuation = {0.0F, 0.0F, 1.0F};
  return desc;
}

std::vector<LightDesc> makeLights() {
  return {
      light(LightType::Directional, {0, 0, 0}, {-0.3F, -1.0F, -0.35F}, {1.0F, 0.93F, 0.80F}, 6.0F),
      light(LightType::Point, {-2.0F, 2.6F, -17.0F}, {0, -1, 0}, {1.0F, 0.75F, 0.45F}, 4.0F),
      light(LightType::Point, {2.0F, 2.6F, -17.0F}, {0, -1, 0}, {1.0F, 0.75F, 0.45F}, 4.0F),
  };
}

SceneCamera makeCamera() {
  SceneCamera camera;
  camera.name = "atrium_camera";
  camera.yfov = 0.9F;
  camera.znear = 0.05F;
  const glm::vec3 eye(0.0F, 3.0F, 19.0F);
  const glm::vec3 target(0.0F, 2.4F, -10.0F);
  camera.world = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
  return camera;
}

}  // namespace

Scene makeAtriumScene() {
  Scene scene;
  scene.name = "atrium";
  scene.meshes = {makeShell(), makeColumn(), makeArcades(), makeCloths(), makeRails()};
  scene.instances.push_back({0, glm::mat4(1.0F)});
  for (const float x : {-kColonnadeX, kColonnadeX}) {
    for (int i = 0; i < kColumnsPerRow; ++i) {
      const float z = -16.0F + kColumnSpacing * static_cast<float>(i);
      scene.instances.push_back({1, glm::translate(glm::mat4(1.0F), glm::vec3(x, 0.0F, z))});
    }
  }
  scene.instances.push_back({2, glm::mat4(1.0F)});
  scene.instances.push_back({3, glm::mat4(1.0F)});
  scene.instances.push_back({4, glm::mat4(1.0F)});
  scene.materials = makeMaterials();
  scene.images.push_back(makeFloorTexture());
  scene.lights = makeLights();
  scene.cameras.push_back(makeCamera());
  scene.computeBounds();
  return scene;
}

}  // namespace lgh
