// The proto/*.json files compiled into the binary (cmake/Embed.cmake), by file name.
#pragma once

#include <map>
#include <string>

namespace lgh::embedded {
const std::map<std::string, std::string>& protoFiles();
}  // namespace lgh::embedded
