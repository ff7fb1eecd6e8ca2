// Compiles and links GLSL programs from glsl/. Sources are embedded in the binary at build time;
// LGH_GLSL_DIR, when set, reads them from that folder instead (edit shaders without rebuilding).
// `#include "include/x.glsl"` is resolved here, once per file, with #line directives so the
// driver's info log points at the right file and line.
#pragma once

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "gl/gl_objects.hpp"

namespace lgh::gl {

struct ShaderStage {
  GLenum type;       // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER, ...
  std::string file;  // relative to glsl/, e.g. "gbuffer.vert"
};

// Source of one file with its includes expanded and `defines` (lines of "#define X Y") inserted
// after #version. Throws lgh::Error(Internal) for a missing file.
std::string preprocessShader(const std::string& file, const std::string& defines = {});

// Builds a program; a compile or link failure throws lgh::Error(Internal) carrying the file name
// and the driver's info log.
Program buildProgram(std::initializer_list<ShaderStage> stages, const std::string& defines = {});
// The same, for stage lists assembled at run time (program variants).
Program buildProgram(const std::vector<ShaderStage>& stages, const std::string& defines = {});

// Convenience: a compute program from one file.
Program buildComputeProgram(const std::string& file, const std::string& defines = {});

}  // namespace lgh::gl
