#include "gl/gl_api.hpp"

#include <cstdio>
#include <cstdlib>

namespace lgh::gl {

namespace detail {
thread_local const Api* tCurrentApi = nullptr;
}

void setCurrentApi(const Api* table) { detail::tCurrentApi = table; }

const Api* currentApi() { return detail::tCurrentApi; }

// A GL call without a current context is a bug in lghd (a GL object destroyed on the wrong
// thread, say). It cannot be reported as an error value from inside a destructor, so it stops the
// process with a message that names the call, rather than crashing inside a driver.
void failNoCurrentContext(const char* function) {
  std::fprintf(stderr, "lghd: %s called on a thread with no current GL context\n", function);
  std::abort();
}

}  // namespace lgh::gl
