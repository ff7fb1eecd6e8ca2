#include <fmt/format.h>

#include "lgh/error.hpp"
#include "lgh/request.hpp"
#include "request/embedded_proto.hpp"

namespace lgh {

const std::string& protoDocument(const std::string& fileName) {
  const auto& files = embedded::protoFiles();
  const auto it = files.find(fileName);
  if (it == files.end()) {
    throw Error(ErrorCode::NotFound, fmt::format("no proto document named '{}'", fileName),
                fileName);
  }
  return it->second;
}

}  // namespace lgh
