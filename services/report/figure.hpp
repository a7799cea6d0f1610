#pragma once
// What a plot is made of: a Figure holds axes stacked top to bottom (e.g. Bode magnitude over
// phase); each Axes holds line and/or marker series, optional horizontal reference lines
// (limits, thresholds) and its labels. Plain data: fill it in, then call render_svg().
//
//   report::Axes magnitude;
//   magnitude.y_label = "|G| [dB]";
//   magnitude.log_x = true;
//   magnitude.series = {report::markers("measured", f, m_db), report::line("fit", f, fit_db)};
//   report::Figure figure;
//   figure.title = "x/u1";
//   figure.axes = {magnitude, phase};
//   report::write_file_atomically(dir / "bode.svg", report::render_svg(figure));
// (GCC's -Wextra warns about designated initialisers that leave members out, so fill members
// one by one or use the helpers at the end.)
#include <optional>
#include <string>
#include <vector>

namespace ambid::report {

enum class Marker { none, circle, square, cross };

struct Style {
  std::string color;        // any SVG colour ("#1f77b4", "red"); empty = next of the palette
  bool line = true;         // join the points with a line
  double line_width = 1.5;  // px
  std::string dash;         // SVG stroke-dasharray, e.g. "6 3"; empty = solid
  Marker marker = Marker::none;
  double marker_size = 3.0;  // px (radius / half side)
};

// One data set. Points with a non-finite coordinate (or <= 0 on a log axis) are left out and
// break the line, so NaN marks a gap.
struct Series {
  std::string label;  // shown in the legend; empty = not listed
  std::vector<double> x;
  std::vector<double> y;
  Style style;
};

// A horizontal line across the whole axes at y = value (an alarm limit, a zone boundary).
struct ReferenceLine {
  double value = 0.0;
  std::string label;  // written above the left end of the line; may be empty
  std::string color = "#888888";
  std::string dash = "4 3";
};

struct Range {
  double lo = 0.0;
  double hi = 1.0;
};

struct Axes {
  std::string title;
  std::string x_label;
  std::string y_label;
  bool log_x = false;
  bool log_y = false;
  std::vector<Series> series;
  std::vector<ReferenceLine> reference_lines;
  std::optional<Range> x_range;  // default: the data (rounded out to ticks / whole decades)
  std::optional<Range> y_range;
  double y_step = 0.0;  // linear y with a y_range: tick spacing (e.g. 90 for degrees); 0: automatic
  bool legend = true;   // draw the legend box when some series has a label
};

struct Figure {
  std::string title;
  double width = 800.0;   // px
  double height = 600.0;  // px, shared by the stacked axes
  std::vector<Axes> axes;
  bool share_x = false;  // one x range for all axes (the union), as for a Bode plot
};

// A series drawn as a line, or as markers only, in the next palette colour.
Series line(std::string label, std::vector<double> x, std::vector<double> y);
Series markers(std::string label, std::vector<double> x, std::vector<double> y, Marker marker = Marker::circle);

}  // namespace ambid::report
