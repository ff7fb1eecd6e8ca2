#include "version.hpp"

namespace lghd {

const char* const kVersion = LGHD_VERSION;
const char* const kBuildType = LGHD_BUILD_TYPE;
const char* const kCompiler = LGHD_COMPILER;
const char* const kImageIo = LGHD_IMAGE_IO;

}  // namespace lghd
