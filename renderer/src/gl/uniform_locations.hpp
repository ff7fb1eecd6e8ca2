// Uniform locations looked up once per program and name, then remembered: the G-buffer pass asked
// GL for some forty per material and three per draw in every frame, and that pass was half of a
// warm thumbnail's render-thread time on the H200 (docs/BENCHMARKS.md). Remembered per GL context
// and program, and forgotten when the context goes: only programs that live as long as their
// context may use it (the surface programs of passes/surface_programs.hpp), since a deleted
// program's name may be given to a new one.
#pragma once

#include "gl/gl_api.hpp"

namespace lgh::gl {

// glGetUniformLocation(program, name) of the current context, asked once.
GLint uniformLocation(GLuint program, const char* name);
// Called by a context before it goes.
void forgetUniformLocations(const Api* context);

}  // namespace lgh::gl
