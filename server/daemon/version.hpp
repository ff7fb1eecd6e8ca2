// What was built: reported by /v1/info, /metrics and --version. The values come from CMake and
// are compiled into version.cpp alone.
#pragma once

namespace lghd {

extern const char* const kVersion;
extern const char* const kBuildType;
extern const char* const kCompiler;
extern const char* const kImageIo;

}  // namespace lghd
