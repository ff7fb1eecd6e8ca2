#include "lightgrid/vpl_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <fmt/format.h>

#include "lgh/error.hpp"

namespace lgh {
namespace {

struct Triangle {
  glm::vec3 p[3];
  const Vertex* v[3];
  const Material* material;
};

float srgbToLinear(std::uint8_t value) {
  const float c = static_cast<float>(value) / 255.0F;
  return c <= 0.04045F ? c / 12.92F : std::pow((c + 0.055F) / 1.055F, 2.4F);
}

// Nearest texel with repeat wrapping; white when the image is missing.
glm::vec3 texel(const Scene& scene, const TextureRef& ref, glm::vec2 uv) {
  if (!ref.valid() || static_cast<std::size_t>(ref.image) >= scene.images.size()) {
    return glm::vec3(1.0F);
  }
  const Image8& image = scene.images[static_cast<std::size_t>(ref.image)];
  if (image.width <= 0 || image.height <= 0 || image.channels < 3) return glm::vec3(1.0F);
  uv -= glm::floor(uv);
  const int x = std::min(static_cast<int>(uv.x * static_cast<float>(image.width)), image.width - 1);
  const int y =
      std::min(static_cast<int>(uv.y * static_cast<float>(image.height)), image.height - 1);
  const std::size_t at = (static_cast<std::size_t>(y) * image.width + x) * image.channels;
  if (at + 2 >= image.pixels.size()) return glm::vec3(1.0F);
  return {srgbToLinear(image.pixels[at]), srgbToLinear(image.pixels[at + 1]),
          srgbToLinear(image.pixels[at + 2])};
}

std::vector<Triangle> worldTriangles(const Scene& scene, std::vector<double>& cumulativeArea) {
  static const Material kDefault;
  std::vector<Triangle> triangles;
  double total = 0.0;
  for (const MeshInstance& instance : scene.instances) {
    if (instance.mesh < 0 || static_cast<std::size_t>(instance.mesh) >= scene.meshes.size()) {
      continue;
    }
    for (const Primitive& primitive :
         scene.meshes[static_cast<std::size_t>(instance.mesh)].primitives) {
      const bool hasMaterial =
          primitive.material >= 0 &&
          static_cast<std::size_t>(primitive.material) < scene.materials.size();
      const Material* material =
          hasMaterial ? &scene.materials[static_cast<std::size_t>(primitive.material)] : &kDefault;
      for (std::size_t i = 0; i + 2 < primitive.indices.size(); i += 3) {
        Triangle triangle{};
        bool ok = true;
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t index = primitive.indices[i + static_cast<std::size_t>(k)];
          ok = ok && index < primitive.vertices.size();
          if (!ok) break;
          triangle.v[k] = &primitive.vertices[index];
          triangle.p[k] = glm::vec3(instance.world * glm::vec4(triangle.v[k]->position, 1.0F));
        }
        if (!ok) continue;
        const double area = 0.5 * glm::length(glm::cross(triangle.p[1] - triangle.p[0],
                                                         triangle.p[2] - triangle.p[0]));
        if (!(area > 0.0) || !std::isfinite(area)) continue;
        triangle.material = material;
        total += area;
        triangles.push_back(triangle);
        cumulativeArea.push_back(total);
      }
    }
  }
  return triangles;
}

// Uniform in [0, 1) from 24 random bits: the same on every standard library.
float uniform01(std::mt19937& rng) { return static_cast<float>(rng() >> 8) * (1.0F / 16777216.0F); }

}  // namespace

std::vector<PointLight> sampleSurfaceVpls(const Scene& scene, const VplSamplerOptions& options) {
  std::vector<PointLight> lights;
  if (options.count <= 0) return lights;
  std::vector<double> cumulative;
  const std::vector<Triangle> triangles = worldTriangles(scene, cumulative);
  if (triangles.empty()) {
    throw Error(ErrorCode::Invalid, "the scene has no surface to place virtual point lights on");
  }
  std::mt19937 rng(options.seed);
  const double totalArea = cumulative.back();
  const float scale = options.totalFlux / static_cast<float>(options.count);
  lights.reserve(static_cast<std::size_t>(options.count));
  for (int i = 0; i < options.count; ++i) {
    const double pick = static_cast<double>(uniform01(rng)) * totalArea;
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), pick);
    const Triangle& t =
        triangles[std::min<std::size_t>(it - cumulative.begin(), triangles.size() - 1)];
    // Uniform point in the triangle: b = (1 - sqrt(r1), sqrt(r1) (1 - r2), sqrt(r1) r2).
    const float s = std::sqrt(uniform01(rng));
    const float r2 = uniform01(rng);
    const float b[3] = {1.0F - s, s * (1.0F - r2), s * r2};
    glm::vec3 position(0.0F);
    glm::vec4 color(0.0F);
    glm::vec2 uv(0.0F);
    for (int k = 0; k < 3; ++k) {
      position += b[k] * t.p[k];
      color += b[k] * t.v[k]->color;
      uv += b[k] * (t.material->baseColorTexture.texCoord == 1 ? t.v[k]->uv1 : t.v[k]->uv0);
    }
    const glm::vec3 albedo = glm::vec3(t.material->baseColorFactor) * glm::vec3(color) *
                             texel(scene, t.material->baseColorTexture, uv);
    PointLight light;
    light.positionPad = glm::vec4(position, 0.0F);
    light.intensityPad = glm::vec4(glm::max(albedo, glm::vec3(0.0F)) * scale, 0.0F);
    lights.push_back(light);
  }
  return lights;
}

void uploadPointLights(const std::vector<PointLight>& lights, gl::SizedBuffer& buffer) {
  for (std::size_t i = 0; i < lights.size(); ++i) {
    if (!lghValidLight(lights[i])) {
      throw Error(ErrorCode::Invalid,
                  fmt::format("point light {} has a NaN, infinite or out-of-range position or "
                              "intensity (|x| <= 1e30, 0 <= intensity <= 1e30)",
                              i),
                  "lights");
    }
  }
  const auto bytes = static_cast<GLsizeiptr>(lights.size() * sizeof(PointLight));
  buffer.reserve(std::max<GLsizeiptr>(bytes, sizeof(PointLight)));
  if (bytes > 0) glNamedBufferSubData(buffer.id(), 0, bytes, lights.data());
}

}  // namespace lgh
