#include <string>

#include "fuzz_targets.hpp"
#include "lgh/error.hpp"
#include "lgh/request.hpp"

namespace lgh::fuzz {

void renderRequest(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const RenderRequest request = parseRenderRequest(text);
    (void)request;
  } catch (const Error&) {
  }
}

}  // namespace lgh::fuzz
