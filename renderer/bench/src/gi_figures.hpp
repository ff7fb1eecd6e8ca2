// Fig. 5 of the paper as images: frames above their overdraw heat maps (a log colour scale), and
// the mean overdraw per pixel against the number of grid lights on log-log axes, with labels
// drawn in a small built-in bitmap font (no font files, no plotting library).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lgh/image.hpp"

namespace lgh::bench {

struct HeatMapPanel {
  std::string label;                    // e.g. "100K VPLs, mean 154"
  FloatImage frame;                     // linear, top row first
  std::vector<std::uint32_t> overdraw;  // per pixel, GL order (row 0 at the bottom)
};

// Panels side by side, each `panelWidth` wide: the tone-mapped frame over its heat map, the
// label under them, and a colour bar of the shared log scale at the bottom.
Image8 overdrawHeatMaps(const std::vector<HeatMapPanel>& panels, int panelWidth);

struct PlotPoint {
  double x = 0.0;  // grid lights
  double y = 0.0;  // mean overdraw per pixel
  std::string label;
};

// The points on log-log axes (decade ticks labelled), joined by a line.
Image8 logLogPlot(const std::vector<PlotPoint>& points, const std::string& xLabel,
                  const std::string& yLabel);

}  // namespace lgh::bench
