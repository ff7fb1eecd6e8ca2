// The GL entry points. Every GL function is resolved through the context's own proc-address
// function (eglGetProcAddress, OSMesaGetProcAddress), once per context, into a table the context
// owns (glad's GladGLContext, generated at build time from the Khronos registry). `glFoo(...)`
// calls the table of the context current on the calling thread: there is no guessing of the
// window system per call, and a GL call on a thread without a current context fails with the
// call's name instead of reaching a driver.
#pragma once

#include <glad/gl.h>

namespace lgh::gl {

using Api = GladGLContext;

// Makes `table` the GL functions of this thread (nullptr: none). GlContext calls it when it
// makes itself current or releases the thread.
void setCurrentApi(const Api* table);
const Api* currentApi();

[[noreturn]] void failNoCurrentContext(const char* function);

namespace detail {
extern thread_local const Api* tCurrentApi;
}

inline const Api& api(const char* function) {
  const Api* table = detail::tCurrentApi;
  if (table == nullptr) [[unlikely]] {
    failNoCurrentContext(function);
  }
  return *table;
}

}  // namespace lgh::gl

#include <gl_api_macros.h>
