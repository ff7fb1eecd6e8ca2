#include "scene/demo_scene.hpp"

#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace lgh {
namespace {

enum DemoMaterial { kFloor, kWhite, kRed, kGreen, kMetal, kPanel };

// Appends a rectangle centred at `center` facing `normal`. The texture's u runs along `uAxis` and
// its "up" (decreasing glTF v) along cross(normal, uAxis), so the tangent frame is right-handed
// (w = +1) and the winding is counter-clockwise seen from the front, as glTF expects.
void addQuad(Primitive& primitive, const glm::vec3& center, const glm::vec3& normal,
             const glm::vec3& uAxis, float halfU, float halfV) {
  const glm::vec3 vAxis = glm::cross(normal, uAxis);
  const glm::vec3 u = uAxis * halfU;
  const glm::vec3 v = vAxis * halfV;
  const auto base = static_cast<std::uint32_t>(primitive.vertices.size());
  const glm::vec3 corners[4] = {center - u - v, center + u - v, center + u + v, center - u + v};
  const glm::vec2 uvs[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  for (int k = 0; k < 4; ++k) {
    Vertex vertex;
    vertex.position = corners[k];
    vertex.normal = normal;
    vertex.tangent = glm::vec4(uAxis, 1.0F);
    vertex.uv0 = uvs[k];
    vertex.uv1 = uvs[k];
    primitive.vertices.push_back(vertex);
  }
  for (std::uint32_t index : {0U, 1U, 2U, 0U, 2U, 3U}) primitive.indices.push_back(base + index);
}

Primitive makeRoomSurface(int material) {
  Primitive primitive;
  primitive.material = material;
  return primitive;
}

Mesh makeRoom() {
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  Primitive floor = makeRoomSurface(kFloor);
  addQuad(floor, {0, 0, 0}, y, x, 1.0F, 1.0F);
  Primitive white = makeRoomSurface(kWhite);
  addQuad(white, {0, 2, 0}, -y, x, 1.0F, 1.0F);  // ceiling
  addQuad(white, {0, 1, -1}, z, x, 1.0F, 1.0F);  // back wall
  Primitive red = makeRoomSurface(kRed);
  addQuad(red, {-1, 1, 0}, x, -z, 1.0F, 1.0F);  // left wall, facing +X into the room
  Primitive green = makeRoomSurface(kGreen);
  addQuad(green, {1, 1, 0}, -x, z, 1.0F, 1.0F);  // right wall, facing -X
  return Mesh{"room", {floor, white, red, green}};
}

// An axis-aligned box standing on y = 0, centred on the Y axis, outward normals.
Mesh makeBox(const std::string& name, const glm::vec3& size, int material) {
  const glm::vec3 h = size * 0.5F;
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  Primitive box = makeRoomSurface(material);
  addQuad(box, {h.x, h.y, 0}, x, -z, h.z, h.y);
  addQuad(box, {-h.x, h.y, 0}, -x, z, h.z, h.y);
  addQuad(box, {0, size.y, 0}, y, x, h.x, h.z);
  addQuad(box, {0, 0, 0}, -y, x, h.x, h.z);
  addQuad(box, {0, h.y, h.z}, z, x, h.x, h.y);
  addQuad(box, {0, h.y, -h.z}, -z, -x, h.x, h.y);
  return Mesh{name, {box}};
}

// UV sphere centred at the origin. u follows longitude (increasing towards +X seen from +Z), v runs
// from 0 at the north pole to 1 at the south pole, so the bitangent points north and w = +1.
Mesh makeSphere(float radius, int rings, int segments, int material) {
  Primitive sphere = makeRoomSurface(material);
  for (int ring = 0; ring <= rings; ++ring) {
    const float theta = glm::pi<float>() * static_cast<float>(ring) / static_cast<float>(rings);
    for (int segment = 0; segment <= segments; ++segment) {
      const float phi =
          glm::two_pi<float>() * static_cast<float>(segment) / static_cast<float>(segments);
      const glm::vec3 direction(std::sin(theta) * std::sin(phi), std::cos(theta),
                                std::sin(theta) * std::cos(phi));
      Vertex vertex;
      vertex.position = direction * radius;
      vertex.normal = direction;
      vertex.tangent = glm::vec4(std::cos(phi), 0.0F, -std::sin(phi), 1.0F);
      vertex.uv0 = glm::vec2(static_cast<float>(segment) / static_cast<float>(segments),
                             static_cast<float>(ring) / static_cast<float>(rings));
      vertex.uv1 = vertex.uv0;
      sphere.vertices.push_back(vertex);
    }
  }
  const auto stride = static_cast<std::uint32_t>(segments + 1);
  for (int ring = 0; ring < rings; ++ring) {
    for (int segment = 0; segment < segments; ++segment) {
      const std::uint32_t a = static_cast<std::uint32_t>(ring) * stride + segment;  // upper left
      const std::uint32_t b = a + stride;                                           // lower left
      // Skip the zero-area triangles that touch a pole twice.
      if (ring != rings - 1) sphere.indices.insert(sphere.indices.end(), {a, b, b + 1});
      if (ring != 0) sphere.indices.insert(sphere.indices.end(), {a, b + 1, a + 1});
    }
  }
  return Mesh{"sphere", {sphere}};
}

Mesh makeCeilingPanel() {
  Primitive panel = makeRoomSurface(kPanel);
  // 1 mm below the ceiling, so the two never z-fight.
  addQuad(panel, {0, 1.999F, 0}, {0, -1, 0}, {1, 0, 0}, 0.25F, 0.25F);
  return Mesh{"ceiling_panel", {panel}};
}

// 256 x 256 sRGB checker, 8 x 8 tiles of 32 pixels.
Image8 makeChecker() {
  constexpr int kSize = 256;
  constexpr int kTile = kSize / 8;
  Image8 image;
  image.width = kSize;
  image.height = kSize;
  image.channels = 4;
  image.pixels.resize(static_cast<std::size_t>(kSize) * kSize * 4);
  for (int py = 0; py < kSize; ++py) {
    for (int px = 0; px < kSize; ++px) {
      const bool light = ((px / kTile) + (py / kTile)) % 2 == 0;
      const std::uint8_t value = light ? 200 : 90;
      std::uint8_t* pixel = &image.pixels[(static_cast<std::size_t>(py) * kSize + px) * 4];
      pixel[0] = pixel[1] = pixel[2] = value;
      pixel[3] = 255;
    }
  }
  return image;
}

Material dielectric(const std::string& name, const glm::vec3& color) {
  Material material;
  material.name = name;
  material.baseColorFactor = glm::vec4(color, 1.0F);
  material.metallicFactor = 0.0F;
  material.roughnessFactor = 0.8F;
  return material;
}

std::vector<Material> makeMaterials() {
  std::vector<Material> materials;
  Material floor = dielectric("floor_checker", glm::vec3(1.0F));
  floor.baseColorTexture.image = 0;
  materials.push_back(floor);
  materials.push_back(dielectric("white", glm::vec3(0.8F)));
  materials.push_back(dielectric("red", glm::vec3(0.63F, 0.065F, 0.05F)));
  materials.push_back(dielectric("green", glm::vec3(0.14F, 0.45F, 0.091F)));
  Material metal = dielectric("metal", glm::vec3(0.95F, 0.93F, 0.88F));
  metal.metallicFactor = 1.0F;
  metal.roughnessFactor = 0.3F;
  materials.push_back(metal);
  Material panel = dielectric("ceiling_panel", glm::vec3(0.8F));
  panel.emissiveFactor = glm::vec3(1.0F, 0.95F, 0.85F);
  materials.push_back(panel);
  return materials;
}

LightDesc makeLight(LightType type, const glm::vec3& position, const glm::vec3& direction,
                    const glm::vec3& color, float intensity) {
  const glm::vec3 d = glm::normalize(direction);
  LightDesc light;
  light.type = type;
  light.position = {position.x, position.y, position.z};
  light.direction = {d.x, d.y, d.z};
  light.color = {color.x, color.y, color.z};
  light.intensity = intensity;
  light.attenuation = {0.0F, 0.0F, 1.0F};  // inverse square, as glTF
  return light;
}

std::vector<LightDesc> makeLights() {
  const glm::vec3 spotPosition(0.8F, 1.8F, 0.9F);
  const glm::vec3 tallBoxCentre(-0.35F, 0.6F, -0.3F);
  LightDesc spot =
      makeLight(LightType::Spot, spotPosition, tallBoxCentre - spotPosition, glm::vec3(1.0F), 5.0F);
  spot.innerConeAngle = 0.25F;
  spot.outerConeAngle = 0.45F;
  return {
      makeLight(LightType::Point, {0.0F, 1.75F, 0.0F}, {0, -1, 0}, {1.0F, 0.95F, 0.85F}, 3.0F),
      spot,
      makeLight(LightType::Directional, {0, 0, 0}, {-0.3F, -0.6F, -0.75F}, {0.8F, 0.85F, 1.0F},
                0.3F),
  };
}

glm::mat4 placed(const glm::vec3& position, float yawDegrees) {
  const glm::mat4 translation = glm::translate(glm::mat4(1.0F), position);
  return glm::rotate(translation, glm::radians(yawDegrees), glm::vec3(0, 1, 0));
}

SceneCamera makeCamera() {
  SceneCamera camera;
  camera.name = "demo_camera";
  camera.perspective = true;
  camera.yfov = 0.8F;
  camera.znear = 0.1F;
  camera.world = glm::translate(glm::mat4(1.0F), glm::vec3(0.0F, 1.0F, 3.5F));
  return camera;
}

}  // namespace

Scene makeDemoScene() {
  constexpr float kShortBoxSize = 0.6F;
  constexpr float kSphereRadius = 0.25F;
  Scene scene;
  scene.name = "demo";
  scene.meshes = {makeRoom(), makeCeilingPanel(), makeBox("tall_box", {0.6F, 1.2F, 0.6F}, kWhite),
                  makeBox("short_box", glm::vec3(kShortBoxSize), kWhite),
                  makeSphere(kSphereRadius, 24, 48, kMetal)};
  scene.instances = {
      {0, glm::mat4(1.0F)},
      {1, glm::mat4(1.0F)},
      {2, placed({-0.35F, 0.0F, -0.3F}, 17.0F)},
      {3, placed({0.4F, 0.0F, 0.3F}, -18.0F)},
      {4, placed({0.4F, kShortBoxSize + kSphereRadius, 0.3F}, 0.0F)},
  };
  scene.materials = makeMaterials();
  scene.images.push_back(makeChecker());
  scene.lights = makeLights();
  scene.cameras.push_back(makeCamera());
  scene.computeBounds();
  return scene;
}

}  // namespace lgh
