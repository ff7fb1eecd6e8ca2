#include "gi/gi_source_buffer.hpp"

#include <algorithm>
#include <cstring>

#include "gl/slots.hpp"

namespace lgh {
namespace {

constexpr float kSurfaceOffset = 1e-4F;

float sceneDiagonal(const Scene& scene) {
  return scene.bounds.empty() ? 1.0F : glm::length(scene.bounds.size());
}

}  // namespace

glm::vec4 giSceneSphere(const Scene& scene) {
  if (scene.bounds.empty()) return {0.0F, 0.0F, 0.0F, 1.0F};
  return {scene.bounds.center(), std::max(0.5F * sceneDiagonal(scene), 1e-6F)};
}

float giSurfaceOffset(const Scene& scene) {
  return std::max(kSurfaceOffset * sceneDiagonal(scene), 1e-6F);
}

const GiSourceTable& GiSourceBuffer::update(const std::vector<LightDesc>& lights,
                                            const HitGeometry& geometry, const Scene& scene) {
  table_ = buildGiSources(lights, geometry.emissiveTriangles(), scene.bounds);
  const std::size_t bytes = table_.sources.size() * sizeof(GiSourceGpu);
  if (table_.sources.size() == uploaded_.size() && buffer_.id() != 0 &&
      std::memcmp(table_.sources.data(), uploaded_.data(), bytes) == 0) {
    return table_;
  }
  buffer_.reserve(static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, sizeof(GiSourceGpu))));
  if (bytes > 0) {
    glNamedBufferSubData(buffer_.id(), 0, static_cast<GLsizeiptr>(bytes), table_.sources.data());
  }
  uploaded_ = table_.sources;
  return table_;
}

void GiSourceBuffer::bind(GLuint lightBuffer) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_SOURCES, buffer_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LGH_BIND_GI_LIGHTS, lightBuffer);
}

void GiSourceBuffer::setUniforms(GLuint program, const Scene& scene) const {
  glProgramUniform1ui(program, glGetUniformLocation(program, "uSourceCount"),
                      static_cast<GLuint>(table_.sources.size()));
  const glm::vec4 sphere = giSceneSphere(scene);
  glProgramUniform4f(program, glGetUniformLocation(program, "uSceneSphere"), sphere.x, sphere.y,
                     sphere.z, sphere.w);
  const glm::vec3 low = scene.bounds.empty() ? glm::vec3(-1.0F) : scene.bounds.min;
  const glm::vec3 high = scene.bounds.empty() ? glm::vec3(1.0F) : scene.bounds.max;
  glProgramUniform3f(program, glGetUniformLocation(program, "uSceneMin"), low.x, low.y, low.z);
  glProgramUniform3f(program, glGetUniformLocation(program, "uSceneMax"), high.x, high.y, high.z);
}

}  // namespace lgh
