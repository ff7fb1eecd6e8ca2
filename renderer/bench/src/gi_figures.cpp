#include "gi_figures.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace lgh::bench {
namespace {

struct Rgb {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
};

class Canvas {
 public:
  Canvas(int width, int height, Rgb background) {
    image_.width = width;
    image_.height = height;
    image_.channels = 4;
    image_.pixels.resize(static_cast<std::size_t>(width) * height * 4);
    for (std::size_t i = 0; i < image_.pixels.size(); i += 4) {
      image_.pixels[i] = background.r;
      image_.pixels[i + 1] = background.g;
      image_.pixels[i + 2] = background.b;
      image_.pixels[i + 3] = 255;
    }
  }
  void set(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= image_.width || y >= image_.height) return;
    std::uint8_t* p = &image_.pixels[(static_cast<std::size_t>(y) * image_.width + x) * 4];
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
  }
  void line(int x0, int y0, int x1, int y1, Rgb c) {
    const int steps = std::max(std::abs(x1 - x0), std::abs(y1 - y0));
    for (int i = 0; i <= steps; ++i) {
      const double t = steps == 0 ? 0.0 : static_cast<double>(i) / steps;
      set(static_cast<int>(std::lround(x0 + t * (x1 - x0))),
          static_cast<int>(std::lround(y0 + t * (y1 - y0))), c);
    }
  }
  void disc(int cx, int cy, int radius, Rgb c) {
    for (int y = -radius; y <= radius; ++y) {
      for (int x = -radius; x <= radius; ++x) {
        if (x * x + y * y <= radius * radius) set(cx + x, cy + y, c);
      }
    }
  }
  Image8 take() { return std::move(image_); }

 private:
  Image8 image_;
};

// A 5 x 7 bitmap font: digits, capitals, lower case as capitals, and a few signs. Each glyph is 7
// rows of 5 bits (bit 4 is the left column).
std::array<std::uint8_t, 7> glyph(char c) {
  if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  switch (c) {
    case '0':
      return {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E};
    case '1':
      return {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E};
    case '2':
      return {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F};
    case '3':
      return {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E};
    case '4':
      return {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02};
    case '5':
      return {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E};
    case '6':
      return {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E};
    case '7':
      return {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08};
    case '8':
      return {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E};
    case '9':
      return {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C};
    case 'A':
      return {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11};
    case 'B':
      return {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E};
    case 'C':
      return {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E};
    case 'D':
      return {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C};
    case 'E':
      return {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F};
    case 'F':
      return {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10};
    case 'G':
      return {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F};
    case 'H':
      return {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11};
    case 'I':
      return {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E};
    case 'J':
      return {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C};
    case 'K':
      return {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11};
    case 'L':
      return {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F};
    case 'M':
      return {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11};
    case 'N':
      return {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11};
    case 'O':
      return {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E};
    case 'P':
      return {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10};
    case 'Q':
      return {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D};
    case 'R':
      return {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11};
    case 'S':
      return {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E};
    case 'T':
      return {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04};
    case 'U':
      return {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E};
    case 'V':
      return {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04};
    case 'W':
      return {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A};
    case 'X':
      return {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11};
    case 'Y':
      return {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04};
    case 'Z':
      return {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F};
    case '.':
      return {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C};
    case ',':
      return {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08};
    case '-':
      return {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00};
    case '+':
      return {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00};
    case '/':
      return {0x01, 0x01, 0x02, 0x04, 0x08, 0x10, 0x10};
    case ':':
      return {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00};
    case '(':
      return {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02};
    case ')':
      return {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08};
    default:
      return {0, 0, 0, 0, 0, 0, 0};
  }
}

constexpr int kGlyphAdvance = 6;

void text(Canvas& canvas, int x, int y, const std::string& s, Rgb color, int scale = 1) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto rows = glyph(s[i]);
    for (int row = 0; row < 7; ++row) {
      for (int col = 0; col < 5; ++col) {
        if ((rows[static_cast<std::size_t>(row)] & (0x10 >> col)) == 0) continue;
        for (int sy = 0; sy < scale; ++sy) {
          for (int sx = 0; sx < scale; ++sx) {
            canvas.set(x + (static_cast<int>(i) * kGlyphAdvance + col) * scale + sx,
                       y + row * scale + sy, color);
          }
        }
      }
    }
  }
}

int textWidth(const std::string& s, int scale = 1) {
  return static_cast<int>(s.size()) * kGlyphAdvance * scale;
}

// A perceptually ordered ramp (dark blue, purple, orange, yellow) for t in [0, 1].
Rgb ramp(double t) {
  static const std::array<std::array<double, 3>, 5> stops{
      {{13, 8, 135}, {126, 3, 168}, {204, 71, 120}, {248, 149, 64}, {240, 249, 33}}};
  t = std::clamp(t, 0.0, 1.0) * 4.0;
  const auto i = std::min<std::size_t>(static_cast<std::size_t>(t), 3);
  const double f = t - static_cast<double>(i);
  const auto mix = [&](int c) {
    return static_cast<std::uint8_t>(std::lround(stops[i][static_cast<std::size_t>(c)] * (1.0 - f) +
                                                 stops[i + 1][static_cast<std::size_t>(c)] * f));
  };
  return {mix(0), mix(1), mix(2)};
}

constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kGrey{150, 150, 150};
constexpr Rgb kBackground{24, 24, 28};

}  // namespace

Image8 overdrawHeatMaps(const std::vector<HeatMapPanel>& panels, int panelWidth) {
  if (panels.empty()) return {};
  const int sourceWidth = panels.front().frame.width;
  const int sourceHeight = panels.front().frame.height;
  const int panelHeight = std::max(1, panelWidth * sourceHeight / std::max(sourceWidth, 1));
  constexpr int kMargin = 8;
  constexpr int kLabel = 14;
  constexpr int kBar = 34;
  const int width = static_cast<int>(panels.size()) * (panelWidth + kMargin) + kMargin;
  const int height = kMargin + 2 * panelHeight + kMargin + kLabel + kBar;
  Canvas canvas(width, height, kBackground);
  std::uint32_t maxCount = 1;
  for (const HeatMapPanel& panel : panels) {
    for (std::uint32_t c : panel.overdraw) maxCount = std::max(maxCount, c);
  }
  const double logMax = std::log(1.0 + maxCount);
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const HeatMapPanel& panel = panels[i];
    const int left = kMargin + static_cast<int>(i) * (panelWidth + kMargin);
    const Image8 display = toDisplay8(panel.frame, ToneMap::Aces, 1.0F, false);
    for (int y = 0; y < panelHeight; ++y) {
      for (int x = 0; x < panelWidth; ++x) {
        const int sx = x * panel.frame.width / panelWidth;
        const int sy = y * panel.frame.height / panelHeight;
        const std::uint8_t* p =
            &display.pixels[(static_cast<std::size_t>(sy) * display.width + sx) * display.channels];
        canvas.set(left + x, kMargin + y, {p[0], p[1], p[2]});
        const std::size_t glIndex =
            static_cast<std::size_t>(panel.frame.height - 1 - sy) * panel.frame.width + sx;
        const double count = glIndex < panel.overdraw.size() ? panel.overdraw[glIndex] : 0.0;
        canvas.set(left + x, kMargin + panelHeight + y, ramp(std::log(1.0 + count) / logMax));
      }
    }
    text(canvas, left, kMargin + 2 * panelHeight + 4, panel.label, kWhite);
  }
  // The colour bar: counts on the shared log scale.
  const int barTop = height - kBar + 6;
  const int barWidth = width - 2 * kMargin;
  for (int x = 0; x < barWidth; ++x) {
    for (int y = 0; y < 8; ++y) {
      canvas.set(kMargin + x, barTop + y, ramp(static_cast<double>(x) / (barWidth - 1)));
    }
  }
  for (const double count : {0.0, 1.0, 10.0, 100.0, 1000.0, 10000.0}) {
    if (count > maxCount) break;
    const int x = kMargin + static_cast<int>(std::log(1.0 + count) / logMax * (barWidth - 1));
    canvas.line(x, barTop + 8, x, barTop + 11, kWhite);
    text(canvas, std::min(x, width - textWidth(std::to_string(static_cast<int>(count))) - 1),
         barTop + 13, std::to_string(static_cast<int>(count)), kWhite);
  }
  return canvas.take();
}

Image8 logLogPlot(const std::vector<PlotPoint>& points, const std::string& xLabel,
                  const std::string& yLabel) {
  constexpr int kWidth = 640;
  constexpr int kHeight = 400;
  constexpr int kLeft = 64;
  constexpr int kRight = 24;
  constexpr int kTop = 24;
  constexpr int kBottom = 56;
  Canvas canvas(kWidth, kHeight, kBackground);
  if (points.empty()) return canvas.take();
  double xMin = 1e300;
  double xMax = 0.0;
  double yMin = 1e300;
  double yMax = 0.0;
  for (const PlotPoint& p : points) {
    xMin = std::min(xMin, std::max(p.x, 1.0));
    xMax = std::max(xMax, std::max(p.x, 1.0));
    yMin = std::min(yMin, std::max(p.y, 0.1));
    yMax = std::max(yMax, std::max(p.y, 0.1));
  }
  const double x0 = std::floor(std::log10(xMin));
  const double x1 = std::max(x0 + 1.0, std::ceil(std::log10(xMax)));
  const double y0 = std::floor(std::log10(yMin));
  const double y1 = std::max(y0 + 1.0, std::ceil(std::log10(yMax)));
  const auto px = [&](double x) {
    return kLeft + static_cast<int>((std::log10(std::max(x, 1.0)) - x0) / (x1 - x0) *
                                    (kWidth - kLeft - kRight));
  };
  const auto py = [&](double y) {
    return kHeight - kBottom -
           static_cast<int>((std::log10(std::max(y, 0.1)) - y0) / (y1 - y0) *
                            (kHeight - kTop - kBottom));
  };
  canvas.line(kLeft, kTop, kLeft, kHeight - kBottom, kGrey);
  canvas.line(kLeft, kHeight - kBottom, kWidth - kRight, kHeight - kBottom, kGrey);
  for (double d = x0; d <= x1; d += 1.0) {
    const int x = px(std::pow(10.0, d));
    canvas.line(x, kHeight - kBottom, x, kHeight - kBottom + 4, kGrey);
    const std::string label = "1E" + std::to_string(static_cast<int>(d));
    text(canvas, x - textWidth(label) / 2, kHeight - kBottom + 8, label, kWhite);
  }
  for (double d = y0; d <= y1; d += 1.0) {
    const int y = py(std::pow(10.0, d));
    canvas.line(kLeft - 4, y, kLeft, y, kGrey);
    const std::string label = "1E" + std::to_string(static_cast<int>(d));
    text(canvas, kLeft - 6 - textWidth(label), y - 3, label, kWhite);
  }
  text(canvas, (kWidth - textWidth(xLabel)) / 2, kHeight - 24, xLabel, kWhite);
  text(canvas, 4, 6, yLabel, kWhite);
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    canvas.line(px(points[i].x), py(points[i].y), px(points[i + 1].x), py(points[i + 1].y),
                Rgb{248, 149, 64});
  }
  for (const PlotPoint& p : points) {
    canvas.disc(px(p.x), py(p.y), 4, Rgb{240, 249, 33});
    text(canvas, px(p.x) + 7, py(p.y) - 10, p.label, kWhite);
  }
  return canvas.take();
}

}  // namespace lgh::bench
