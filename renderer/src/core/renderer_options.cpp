#include "lgh/renderer_options.hpp"

#include "lgh/error.hpp"

namespace lgh {

ContextBackend parseContextBackend(const std::string& name) {
  if (const auto backend = enumFromName<ContextBackend>(name)) return *backend;
  throw Error(ErrorCode::BadRequest,
              "unknown context backend '" + name + "' (" + enumNameList<ContextBackend>() + ")",
              "backend");
}

const char* contextBackendName(ContextBackend backend) {
  // The table's names are string literals, so the view's data is NUL-terminated.
  return enumName(backend).data();
}

}  // namespace lgh
