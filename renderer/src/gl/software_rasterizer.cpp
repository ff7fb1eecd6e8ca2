#include "gl/software_rasterizer.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "gl/gl_api.hpp"

namespace lgh::gl {

bool softwareRasterizer() {
  const auto* text = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  std::string renderer = text != nullptr ? text : "";
  std::transform(renderer.begin(), renderer.end(), renderer.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* name : {"llvmpipe", "softpipe", "swrast", "lavapipe", "swiftshader"}) {
    if (renderer.find(name) != std::string::npos) return true;
  }
  return false;
}

}  // namespace lgh::gl
