// What was built: reported by /v1/info, /metrics and --version.
#pragma once

namespace lghd {

inline constexpr const char* kVersion = LGHD_VERSION;
inline constexpr const char* kBuildType = LGHD_BUILD_TYPE;
inline constexpr const char* kCompiler = LGHD_COMPILER;
inline constexpr const char* kImageIo = LGHD_IMAGE_IO;

}  // namespace lghd
