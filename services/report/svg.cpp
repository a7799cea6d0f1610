// Drawing of a laid-out figure as SVG text.
#include "services/report/svg.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <sstream>

#include "services/report/layout_metrics.hpp"
#include "services/report/xml_escape.hpp"

namespace ambid::report {
namespace {

// The Tableau 10 palette: distinct, and readable for most colour-blind viewers.
constexpr std::array<const char*, 10> palette = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                                 "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

std::string series_color(const Series& series, std::size_t index) {
  return series.style.color.empty() ? palette[index % palette.size()] : series.style.color;
}

void text(std::ostringstream& svg, double x, double y, const std::string& content, const char* anchor,
          const std::string& extra = "") {
  svg << "<text x=\"" << number(x) << "\" y=\"" << number(y) << "\" text-anchor=\"" << anchor << "\"" << extra << ">"
      << xml_escape(content) << "</text>\n";
}

void draw_grid_and_ticks(std::ostringstream& svg, const AxesLayout& layout) {
  const double bottom = layout.top + layout.height;
  const double right = layout.left + layout.width;
  // Grid lines across the plot at the ticks: minor ones lighter, drawn first.
  const auto grid = [&](const std::vector<double>& x_values, const std::vector<double>& y_values, const char* extra) {
    for (const double value : x_values) {
      const double x = layout.x_scale.to_pixel(value);
      svg << "<line x1=\"" << number(x) << "\" y1=\"" << number(layout.top) << "\" x2=\"" << number(x) << "\" y2=\""
          << number(bottom) << "\"" << extra << "/>\n";
    }
    for (const double value : y_values) {
      const double y = layout.y_scale.to_pixel(value);
      svg << "<line x1=\"" << number(layout.left) << "\" y1=\"" << number(y) << "\" x2=\"" << number(right)
          << "\" y2=\"" << number(y) << "\"" << extra << "/>\n";
    }
  };
  svg << "<g class=\"grid\" stroke=\"#e6e6e6\" stroke-width=\"1\">\n";
  grid(layout.x_ticks.minor, layout.y_ticks.minor, " stroke=\"#f2f2f2\"");
  grid(layout.x_ticks.major, layout.y_ticks.major, "");
  svg << "</g>\n<g class=\"tick-labels\">\n";
  for (std::size_t i = 0; i < layout.x_ticks.major.size(); ++i) {
    text(svg, layout.x_scale.to_pixel(layout.x_ticks.major[i]), bottom + 15, layout.x_ticks.labels[i], "middle");
  }
  for (std::size_t i = 0; i < layout.y_ticks.major.size(); ++i) {
    text(svg, layout.left - 6, layout.y_scale.to_pixel(layout.y_ticks.major[i]) + 4, layout.y_ticks.labels[i], "end");
  }
  svg << "</g>\n";
}

void draw_reference_lines(std::ostringstream& svg, const Axes& axes, const AxesLayout& layout) {
  for (const ReferenceLine& line : axes.reference_lines) {
    if (!layout.y_scale.drawable(line.value)) continue;
    const double y = layout.y_scale.to_pixel(line.value);
    svg << "<line class=\"reference\" x1=\"" << number(layout.left) << "\" y1=\"" << number(y) << "\" x2=\""
        << number(layout.left + layout.width) << "\" y2=\"" << number(y) << "\" stroke=\"" << xml_escape(line.color)
        << "\" stroke-dasharray=\"" << xml_escape(line.dash) << "\"/>\n";
    if (!line.label.empty()) {
      text(svg, layout.left + 4, y - 3, line.label, "start", " fill=\"" + xml_escape(line.color) + "\"");
    }
  }
}

void draw_marker(std::ostringstream& svg, Marker marker, double x, double y, double size) {
  switch (marker) {
    case Marker::circle:
      svg << "<circle cx=\"" << number(x) << "\" cy=\"" << number(y) << "\" r=\"" << number(size) << "\"/>";
      break;
    case Marker::square:
      svg << "<rect x=\"" << number(x - size) << "\" y=\"" << number(y - size) << "\" width=\"" << number(2 * size)
          << "\" height=\"" << number(2 * size) << "\"/>";
      break;
    case Marker::cross:
      svg << "<path d=\"M" << number(x - size) << " " << number(y - size) << "L" << number(x + size) << " "
          << number(y + size) << "M" << number(x - size) << " " << number(y + size) << "L" << number(x + size) << " "
          << number(y - size) << "\" fill=\"none\"/>";
      break;
    case Marker::none:
      break;
  }
}

void draw_series(std::ostringstream& svg, const Series& series, const std::string& color, const AxesLayout& layout) {
  const auto drawable = [&](std::size_t i) {
    return layout.x_scale.drawable(series.x[i]) && layout.y_scale.drawable(series.y[i]);
  };
  if (series.style.line) {
    // One path; a point that cannot be drawn ends the current piece ("M" starts the next).
    std::string d;
    bool pen_down = false;
    for (std::size_t i = 0; i < series.x.size(); ++i) {
      if (!drawable(i)) {
        pen_down = false;
        continue;
      }
      d += (pen_down ? "L" : "M") + number(layout.x_scale.to_pixel(series.x[i])) + " " +
           number(layout.y_scale.to_pixel(series.y[i]));
      pen_down = true;
    }
    if (!d.empty()) {
      svg << "<path class=\"series\" d=\"" << d << "\" fill=\"none\" stroke=\"" << xml_escape(color)
          << "\" stroke-width=\"" << number(series.style.line_width) << "\"";
      if (!series.style.dash.empty()) {
        svg << " stroke-dasharray=\"" << xml_escape(series.style.dash) << "\"";
      }
      svg << "/>\n";
    }
  }
  if (series.style.marker == Marker::none) return;
  const bool filled = series.style.marker != Marker::cross;
  svg << "<g class=\"markers\" " << (filled ? "fill" : "stroke") << "=\"" << xml_escape(color) << "\""
      << (filled ? "" : " stroke-width=\"1.2\"") << ">";
  for (std::size_t i = 0; i < series.x.size(); ++i) {
    if (!drawable(i)) continue;
    draw_marker(svg, series.style.marker, layout.x_scale.to_pixel(series.x[i]), layout.y_scale.to_pixel(series.y[i]),
                series.style.marker_size);
  }
  svg << "</g>\n";
}

void draw_legend(std::ostringstream& svg, const Axes& axes, const AxesLayout& layout) {
  std::size_t rows = 0;
  std::size_t longest = 0;
  for (const Series& series : axes.series) {
    if (series.label.empty()) continue;
    ++rows;
    longest = std::max(longest, series.label.size());
  }
  if (!axes.legend || rows == 0) return;
  const double width = 40.0 + metrics::char_width * static_cast<double>(longest);
  const double height = 6.0 + metrics::legend_row_height * static_cast<double>(rows);
  const double left = layout.left + layout.width - width - 6.0;
  const double top = layout.top + 6.0;
  svg << "<g class=\"legend\">\n<rect x=\"" << number(left) << "\" y=\"" << number(top) << "\" width=\""
      << number(width) << "\" height=\"" << number(height)
      << "\" fill=\"white\" fill-opacity=\"0.85\" stroke=\"#bbbbbb\"/>\n";
  double y = top + 3.0 + metrics::legend_row_height / 2;
  for (std::size_t i = 0; i < axes.series.size(); ++i) {
    const Series& series = axes.series[i];
    if (series.label.empty()) continue;
    const std::string color = series_color(series, i);
    if (series.style.line) {
      svg << "<line x1=\"" << number(left + 6) << "\" y1=\"" << number(y) << "\" x2=\"" << number(left + 28)
          << "\" y2=\"" << number(y) << "\" stroke=\"" << xml_escape(color) << "\" stroke-width=\""
          << number(series.style.line_width) << "\"/>\n";
    }
    if (series.style.marker != Marker::none) {
      const bool filled = series.style.marker != Marker::cross;
      svg << "<g " << (filled ? "fill" : "stroke") << "=\"" << xml_escape(color) << "\">";
      draw_marker(svg, series.style.marker, left + 17, y, series.style.marker_size);
      svg << "</g>\n";
    }
    text(svg, left + 34, y + 4, series.label, "start");
    y += metrics::legend_row_height;
  }
  svg << "</g>\n";
}

void draw_axes(std::ostringstream& svg, const Axes& axes, const AxesLayout& layout, std::size_t index) {
  const double bottom = layout.top + layout.height;
  const std::string clip = "plot-area-" + std::to_string(index);
  svg << "<g class=\"axes\">\n<clipPath id=\"" << clip << "\"><rect x=\"" << number(layout.left) << "\" y=\""
      << number(layout.top) << "\" width=\"" << number(layout.width) << "\" height=\"" << number(layout.height)
      << "\"/></clipPath>\n";
  draw_grid_and_ticks(svg, layout);
  svg << "<g clip-path=\"url(#" << clip << ")\">\n";
  draw_reference_lines(svg, axes, layout);
  for (std::size_t i = 0; i < axes.series.size(); ++i) {
    draw_series(svg, axes.series[i], series_color(axes.series[i], i), layout);
  }
  svg << "</g>\n<rect x=\"" << number(layout.left) << "\" y=\"" << number(layout.top) << "\" width=\""
      << number(layout.width) << "\" height=\"" << number(layout.height) << "\" fill=\"none\" stroke=\"#333333\"/>\n";
  draw_legend(svg, axes, layout);
  if (!axes.title.empty()) {
    text(svg, layout.left + layout.width / 2, layout.top - 8, axes.title, "middle", " font-weight=\"bold\"");
  }
  if (!axes.x_label.empty()) {
    text(svg, layout.left + layout.width / 2, bottom + metrics::tick_label_height + 12, axes.x_label, "middle");
  }
  if (!axes.y_label.empty()) {
    const double x = 16.0;
    const double y = layout.top + layout.height / 2;
    text(svg, x, y, axes.y_label, "middle", " transform=\"rotate(-90 " + number(x) + " " + number(y) + ")\"");
  }
  svg << "</g>\n";
}

}  // namespace

std::string render_svg(const Figure& figure) {
  const std::vector<AxesLayout> layouts = layout_figure(figure);
  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << number(figure.width) << "\" height=\""
      << number(figure.height) << "\" viewBox=\"0 0 " << number(figure.width) << " " << number(figure.height)
      << "\" font-family=\"sans-serif\" font-size=\"" << number(metrics::font_size) << "\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if (!figure.title.empty()) {
    text(svg, figure.width / 2, 20, figure.title, "middle", " font-size=\"15\" font-weight=\"bold\"");
  }
  for (std::size_t i = 0; i < layouts.size(); ++i) draw_axes(svg, figure.axes[i], layouts[i], i);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace ambid::report
