// The test oracle for scenes that crossed a boundary (the scene parser worker's messages, its
// process): every field of lgh::Scene the renderer reads, compared with gtest's EXPECTs.
#pragma once

#include "scene/scene.hpp"

namespace lgh::test {

void expectSameScene(const Scene& a, const Scene& b);

}  // namespace lgh::test
