#pragma once
// Renders a Figure as a standalone SVG document (UTF-8, no scripts, no external resources).
#include <string>
#include <vector>

#include "services/report/figure.hpp"
#include "services/report/scale.hpp"
#include "services/report/ticks.hpp"

namespace ambid::report {

// Where one Axes is drawn: its plot rectangle (pixels) and the ticks/scales in use. Exposed so
// callers and tests can find where a data point lands.
struct AxesLayout {
  double left = 0.0;
  double top = 0.0;
  double width = 0.0;
  double height = 0.0;
  Ticks x_ticks;
  Ticks y_ticks;
  Scale x_scale{0.0, 1.0, 0.0, 1.0, false};
  Scale y_scale{0.0, 1.0, 1.0, 0.0, false};
};

// Layout of every axes of the figure, top to bottom. Throws ambid::Error when the figure cannot
// be drawn: no axes, non-positive size, series with x and y of different lengths, or an axes
// with no drawable point and no explicit range.
std::vector<AxesLayout> layout_figure(const Figure& figure);

std::string render_svg(const Figure& figure);

}  // namespace ambid::report
