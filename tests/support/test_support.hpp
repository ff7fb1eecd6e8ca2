// Shared helpers for the test suite: where test data lives, one renderer per test process, and
// image comparison with a documented metric that writes the actual and a difference image on
// failure.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "lgh/image.hpp"
#include "lgh/renderer_options.hpp"

namespace lgh::test {

// tests/ in the source tree.
std::filesystem::path dataDir();
// Where tests write their outputs (actual and difference images): <build>/test-output.
std::filesystem::path outputDir();
// /usr/share/assimp/models/glTF2 (Debian package assimp-testmodels).
std::filesystem::path assimpGltfDir();

// Renderer options for in-process renderers: the context path comes from LGH_BACKEND when set,
// as it does for lghd, lgh-render and lgh-bench, so the whole suite runs on any path
// (scripts/run-tests runs it again with LGH_BACKEND=osmesa); the upload staging memory from
// LGH_UPLOAD_STAGING_MB (MiB) likewise.
RendererOptions rendererOptions();

// A binary glTF (GLB) of one mesh of triangles, no normals (the loader computes flat ones), one
// node, the default material: for scenes built in a test.
using Position = std::array<float, 3>;
std::vector<std::uint8_t> makeTriangleGlb(const std::vector<Position>& positions,
                                          const std::vector<std::uint32_t>& indices);
// Two triangles of an axis-aligned square at height y, facing up, appended to a mesh.
void addSquare(std::vector<Position>& positions, std::vector<std::uint32_t>& indices, float y,
               float halfSize);

}  // namespace lgh::test

namespace lgh::test {

// Difference of two 8-bit images of equal size, over RGB(A) channels on a 0..255 scale.
struct ImageDifference {
  double meanAbsoluteError = 0.0;      // mean over all channel values
  double fractionOverThreshold = 0.0;  // pixels with any channel differing by more than threshold
  int maxError = 0;
};
ImageDifference compareImages(const Image8& actual, const Image8& expected, int threshold);

// The golden-image check. Metric: mean absolute error (0..255) <= maxMeanError AND the fraction
// of pixels with a channel off by more than 16 <= maxFraction. On failure, or when no baseline
// exists, writes <name>.actual.png and <name>.diff.png (|difference| x 8) to outputDir();
// with LGH_UPDATE_GOLDEN=1 it (re)writes tests/golden/<name>.png instead of comparing.
// Returns an empty string when it passes, else the reason.
std::string checkGolden(const Image8& actual, const std::string& name, double maxMeanError,
                        double maxFraction);

}  // namespace lgh::test
