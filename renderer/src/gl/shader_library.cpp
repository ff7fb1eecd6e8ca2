#include "gl/shader_library.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "lgh/error.hpp"

namespace lgh::embedded {
const std::map<std::string, std::string>& glslSources();
}

namespace lgh::gl {
namespace {

std::string readSource(const std::string& file) {
  if (const char* dir = std::getenv("LGH_GLSL_DIR"); dir != nullptr && *dir != '\0') {
    std::ifstream in(std::filesystem::path(dir) / file);
    if (!in) {
      throw Error(ErrorCode::Internal, fmt::format("shader file not found in {}", dir), file);
    }
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  const auto& sources = embedded::glslSources();
  auto it = sources.find(file);
  if (it == sources.end()) throw Error(ErrorCode::Internal, "shader source not embedded", file);
  return it->second;
}

// The file's numbers for #line: GLSL takes a source-string number, not a name.
int fileNumber(const std::string& file, std::map<std::string, int>& numbers) {
  auto [it, inserted] = numbers.emplace(file, static_cast<int>(numbers.size()));
  return it->second;
}

void expandIncludes(const std::string& file, std::set<std::string>& included,
                    std::map<std::string, int>& numbers, std::string& out, int depth) {
  if (depth > 16) throw Error(ErrorCode::Internal, "#include nested too deeply", file);
  std::istringstream lines(readSource(file));
  std::string line;
  int lineNumber = 0;
  const int thisFile = fileNumber(file, numbers);
  while (std::getline(lines, line)) {
    ++lineNumber;
    auto pos = line.find("#include");
    if (pos != std::string::npos && line.find_first_not_of(" \t") == pos) {
      auto open = line.find('"', pos);
      auto close = line.find('"', open + 1);
      if (open == std::string::npos || close == std::string::npos) {
        throw Error(ErrorCode::Internal, fmt::format("malformed #include at line {}", lineNumber),
                    file);
      }
      std::string target = line.substr(open + 1, close - open - 1);
      if (included.insert(target).second) {
        out += fmt::format("#line 1 {}\n", fileNumber(target, numbers));
        expandIncludes(target, included, numbers, out, depth + 1);
        out += fmt::format("#line {} {}\n", lineNumber + 1, thisFile);
      }
      continue;
    }
    out += line;
    out += '\n';
  }
}

std::string fileTable(const std::map<std::string, int>& numbers) {
  std::string table;
  for (const auto& [name, number] : numbers) table += fmt::format("  {} = {}\n", number, name);
  return table;
}

}  // namespace

std::string preprocessShader(const std::string& file, const std::string& defines) {
  std::string body;
  std::set<std::string> included{file};
  std::map<std::string, int> numbers;
  expandIncludes(file, included, numbers, body, 0);
  // #version must come first: move it above the defines.
  auto versionPos = body.find("#version");
  if (versionPos == std::string::npos) throw Error(ErrorCode::Internal, "no #version line", file);
  auto versionEnd = body.find('\n', versionPos);
  std::string version = body.substr(versionPos, versionEnd - versionPos + 1);
  body.erase(versionPos, versionEnd - versionPos + 1);
  return version + defines + (defines.empty() || defines.back() == '\n' ? "" : "\n") +
         "#line 1 0\n" + body;
}

namespace {

std::string shaderLog(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return log.c_str();
}

std::string programLog(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  return log.c_str();
}

Shader compileStage(const ShaderStage& stage, const std::string& defines) {
  std::string source = preprocessShader(stage.file, defines);
  Shader shader(stage.type);
  const char* text = source.c_str();
  glShaderSource(shader.id(), 1, &text, nullptr);
  glCompileShader(shader.id());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    std::set<std::string> included{stage.file};
    std::map<std::string, int> numbers;
    std::string ignored;
    expandIncludes(stage.file, included, numbers, ignored, 0);
    throw Error(ErrorCode::Internal,
                fmt::format("GLSL compile failed:\n{}source-string numbers:\n{}",
                            shaderLog(shader.id()), fileTable(numbers)),
                stage.file);
  }
  return shader;
}

}  // namespace

Program buildProgram(std::initializer_list<ShaderStage> stages, const std::string& defines) {
  return buildProgram(std::vector<ShaderStage>(stages), defines);
}

Program buildProgram(const std::vector<ShaderStage>& stages, const std::string& defines) {
  Program program;
  std::vector<Shader> shaders;
  std::string names;
  for (const auto& stage : stages) {
    shaders.push_back(compileStage(stage, defines));
    glAttachShader(program.id(), shaders.back().id());
    names += (names.empty() ? "" : "+") + stage.file;
  }
  glLinkProgram(program.id());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  for (const auto& shader : shaders) glDetachShader(program.id(), shader.id());
  if (ok != GL_TRUE) {
    throw Error(ErrorCode::Internal, "GLSL link failed:\n" + programLog(program.id()), names);
  }
  return program;
}

Program buildComputeProgram(const std::string& file, const std::string& defines) {
  return buildProgram({{GL_COMPUTE_SHADER, file}}, defines);
}

}  // namespace lgh::gl
