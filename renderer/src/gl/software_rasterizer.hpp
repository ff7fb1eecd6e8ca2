// Whether the current GL context renders on the CPU (Mesa's llvmpipe and kin): passes that choose
// a formulation by device ask this, since a CPU's SIMD lanes and thread pool favour other shapes
// of work than a GPU's (docs/BENCHMARKS.md).
#pragma once

namespace lgh::gl {

// From GL_RENDERER of the current context.
bool softwareRasterizer();

}  // namespace lgh::gl
