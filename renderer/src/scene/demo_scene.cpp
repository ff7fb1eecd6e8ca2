#include "scene/demo_scene.hpp"

#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/procedural_textures.hpp"

namespace lgh {
namespace {

enum DemoMaterial {
  kFloor,
  kWhite,
  kRed,
  kGreen,
  kMetal,
  kPanel,
  // The row of the lecture's illumination models, front of the room, left to right.
  kModelGgx,
  kModelPhong,
  kModelBlinnPhong,
  kModelLambert,
  kModelOrenNayar,
  kModelCookTorrance,
};
constexpr int kModelRowFirst = kModelGgx;
constexpr int kModelRowCount = 6;

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
  primitive.tangents = true;  // every generator below writes a right-handed frame
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

// One small sphere per illumination model, named after it.
Mesh makeModelSphere(int material, const std::string& name) {
  Mesh mesh = makeSphere(0.1F, 16, 32, material);
  mesh.name = name;
  return mesh;
}

Mesh makeCeilingPanel() {
  Primitive panel = makeRoomSurface(kPanel);
  // 1 mm below the ceiling, so the two never z-fight.
  addQuad(panel, {0, 1.999F, 0}, {0, -1, 0}, {1, 0, 0}, 0.25F, 0.25F);
  return Mesh{"ceiling_panel", {panel}};
}

// The demo's images, also its textures (Scene::textures, by the same index): what a request's
// material parameters may name.
enum DemoTexture {
  kCheckerTexture,
  kBrickHeightTexture,
  kBrickNormalTexture,
  kLightMapTexture,
  kBrickColorTexture
};

std::vector<Image8> makeImages() {
  const Image8 bricks = makeBrickHeightImage(128, 8);
  return {makeCheckerImage(256, 8, 200, 90), bricks, makeNormalMapImage(bricks, 6.0F),
          makeLightMapImage(64), makeBrickColorImage(128, 8)};
}

Material dielectric(const std::string& name, const glm::vec3& color) {
  Material material;
  material.name = name;
  material.baseColorFactor = glm::vec4(color, 1.0F);
  material.metallicFactor = 0.0F;
  material.roughnessFactor = 0.8F;
  return material;
}

// The lecture's models side by side, all the same clay colour (Cook-Torrance as plastic).
void addModelRowMaterials(std::vector<Material>& materials) {
  const glm::vec3 clay(0.75F, 0.42F, 0.25F);
  Material ggx = dielectric("model_metallic_roughness", clay);
  ggx.roughnessFactor = 0.35F;
  materials.push_back(ggx);
  Material phong = dielectric("model_phong", clay);
  phong.model = MaterialModel::Phong;
  phong.classic.specular = glm::vec3(0.6F);
  phong.classic.shininess = 40.0F;
  materials.push_back(phong);
  Material blinn = phong;
  blinn.name = "model_blinn_phong";
  blinn.model = MaterialModel::BlinnPhong;
  blinn.classic.shininess = 160.0F;  // about Phong's highlight at 40: N.H's angle is half R.V's
  materials.push_back(blinn);
  Material lambert = dielectric("model_lambert", clay);
  lambert.model = MaterialModel::OrenNayar;
  lambert.classic.sigma = 0.0F;
  materials.push_back(lambert);
  Material orenNayar = lambert;
  orenNayar.name = "model_oren_nayar";
  orenNayar.classic.sigma = 0.8F;
  materials.push_back(orenNayar);
  Material cookTorrance = dielectric("model_cook_torrance", clay);
  cookTorrance.model = MaterialModel::CookTorrance;
  cookTorrance.classic.f0 = glm::vec3(0.04F);  // plastic
  cookTorrance.classic.m = 0.15F;
  materials.push_back(cookTorrance);
}

std::vector<Material> makeMaterials() {
  std::vector<Material> materials;
  Material floor = dielectric("floor_checker", glm::vec3(1.0F));
  floor.baseColorTexture.image = kCheckerTexture;
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
  addModelRowMaterials(materials);
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
  static const char* const kRowNames[kModelRowCount] = {
      "ggx_sphere",     "phong_sphere",      "blinn_phong_sphere",
      "lambert_sphere", "oren_nayar_sphere", "cook_torrance_sphere"};
  for (int i = 0; i < kModelRowCount; ++i) {
    scene.meshes.push_back(makeModelSphere(kModelRowFirst + i, kRowNames[i]));
    const float x = -0.75F + 0.3F * static_cast<float>(i);
    scene.instances.push_back(
        {static_cast<int>(scene.meshes.size()) - 1, placed({x, 0.1F, 0.82F}, 0.0F)});
  }
  scene.materials = makeMaterials();
  scene.images = makeImages();
  for (int image = 0; image < static_cast<int>(scene.images.size()); ++image) {
    TextureRef texture;
    texture.image = image;
    scene.textures.push_back(texture);
  }
  scene.lights = makeLights();
  scene.cameras.push_back(makeCamera());
  scene.computeBounds();
  return scene;
}

}  // namespace lgh
