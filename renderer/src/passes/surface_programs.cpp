#include "passes/surface_programs.hpp"

#include <string>
#include <vector>

#include "gl/shader_library.hpp"

namespace lgh {

SurfaceProgram& SurfacePrograms::get(const SurfaceProgramKey& key) {
  if (const auto it = programs_.find(key); it != programs_.end()) return it->second;
  std::vector<gl::ShaderStage> stages{{GL_VERTEX_SHADER, "gbuffer.vert"}};
  std::string defines;
  if (key.features != kAllMaterialFeatures) {
    defines += "#define LGH_MATERIAL_FEATURES " + std::to_string(key.features) + "\n";
  }
  const bool triangles = key.topology == Topology::Triangles;
  if (triangles && key.shading == ShadingMode::Gouraud) defines += "#define LGH_GOURAUD\n";
  if (triangles && key.displaced) {
    defines += "#define LGH_DISPLACED 1\n";
    stages.push_back({GL_TESS_CONTROL_SHADER, "gbuffer_displace.tesc"});
    stages.push_back({GL_TESS_EVALUATION_SHADER, "gbuffer_displace.tese"});
  }
  if (key.topology == Topology::Lines) {
    stages.push_back({GL_GEOMETRY_SHADER, "gbuffer_lines.geom"});
  } else if (key.topology == Topology::Points) {
    stages.push_back({GL_GEOMETRY_SHADER, "gbuffer_points.geom"});
  } else if (key.shading == ShadingMode::Flat) {
    stages.push_back({GL_GEOMETRY_SHADER, "gbuffer_flat.geom"});
  }
  stages.push_back({GL_FRAGMENT_SHADER, key.forward ? "forward_blend.frag" : "gbuffer.frag"});
  return programs_.emplace(key, SurfaceProgram(gl::buildProgram(stages, defines))).first->second;
}

}  // namespace lgh
