# cmake -DINPUT=glad/gl.h -DOUTPUT=gl_api_macros.h -P GlApiMacros.cmake
# One macro per function pointer of glad's GladGLContext: glFoo -> the current context's Foo. The
# name goes along so that a call on a thread without a current context says which call it was.
file(STRINGS "${INPUT}" lines REGEX "^    PFNGL[A-Z0-9_]+PROC [A-Za-z0-9_]+;$")
set(text "// Generated from glad/gl.h by cmake/GlApiMacros.cmake. Do not edit.\n#pragma once\n")
foreach(line IN LISTS lines)
  string(REGEX REPLACE "^    PFNGL[A-Z0-9_]+PROC ([A-Za-z0-9_]+);$" "\\1" name "${line}")
  string(APPEND text "#define gl${name} (::lgh::gl::api(\"gl${name}\").${name})\n")
endforeach()
list(LENGTH lines count)
if(count LESS 500)
  message(FATAL_ERROR "GlApiMacros: only ${count} GL functions found in ${INPUT}")
endif()
file(WRITE "${OUTPUT}" "${text}")
