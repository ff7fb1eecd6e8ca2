#include <spdlog/spdlog.h>

#include "fuzz_targets.hpp"

namespace lgh::fuzz {

void setUpQuietLogging() { spdlog::set_level(spdlog::level::off); }

}  // namespace lgh::fuzz
