#include "fuzz_targets.hpp"
#include "lgh/error.hpp"
#include "lgh/image.hpp"

namespace lgh::fuzz {

void textureDecoder(const std::uint8_t* data, std::size_t size) {
  try {
    const Image8 image = image_io::decodeTextureRgba8(data, size, "fuzz input");
    (void)image;
  } catch (const Error&) {
  }
}

}  // namespace lgh::fuzz
