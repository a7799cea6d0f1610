// Where each axes of a figure goes and which data range it shows.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.hpp"
#include "services/report/layout_metrics.hpp"
#include "services/report/svg.hpp"

namespace ambid::report {
namespace {

struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double value) {
    lo = std::min(lo, value);
    hi = std::max(hi, value);
  }
  void add(const Extent& other) {
    lo = std::min(lo, other.lo);
    hi = std::max(hi, other.hi);
  }
  bool empty() const { return lo > hi; }
};

bool usable(double value, bool log) { return std::isfinite(value) && (!log || value > 0.0); }

void check_series(const Axes& axes, std::size_t index) {
  for (const Series& series : axes.series) {
    if (series.x.size() != series.y.size()) {
      std::ostringstream message;
      message << "axes " << index << " series '" << series.label << "' has " << series.x.size() << " x values but "
              << series.y.size() << " y values";
      throw Error(message.str());
    }
  }
}

// Data extent of the points drawable on both axes (a point with a NaN y does not widen x).
std::pair<Extent, Extent> data_extent(const Axes& axes) {
  Extent x;
  Extent y;
  for (const Series& series : axes.series) {
    for (std::size_t i = 0; i < series.x.size(); ++i) {
      if (usable(series.x[i], axes.log_x) && usable(series.y[i], axes.log_y)) {
        x.add(series.x[i]);
        y.add(series.y[i]);
      }
    }
  }
  for (const ReferenceLine& line : axes.reference_lines) {
    if (usable(line.value, axes.log_y)) y.add(line.value);
  }
  return {x, y};
}

Ticks choose_ticks(const std::optional<Range>& fixed, const Extent& data, bool log, const char* axis_name,
                   std::size_t index, double step = 0.0) {
  if (fixed && step > 0.0 && !log) return linear_ticks_with_step(fixed->lo, fixed->hi, step);
  if (fixed) return log ? log_ticks_fixed(fixed->lo, fixed->hi) : linear_ticks_fixed(fixed->lo, fixed->hi);
  if (data.empty()) {
    std::ostringstream message;
    message << "axes " << index << " has no drawable point for its " << axis_name << " axis (all values non-finite"
            << (log ? " or not positive" : "") << ") and no explicit range";
    throw Error(message.str());
  }
  return log ? log_ticks(data.lo, data.hi) : linear_ticks(data.lo, data.hi);
}

}  // namespace

std::vector<AxesLayout> layout_figure(const Figure& figure) {
  if (figure.axes.empty()) throw Error("figure '" + figure.title + "' has no axes");
  if (!(figure.width > 2 * metrics::margin_left) || !(figure.height > 0.0)) {
    std::ostringstream message;
    message << "figure size " << figure.width << " x " << figure.height << " px is too small";
    throw Error(message.str());
  }
  std::vector<std::pair<Extent, Extent>> extents;
  Extent shared_x;
  for (std::size_t i = 0; i < figure.axes.size(); ++i) {
    check_series(figure.axes[i], i);
    extents.push_back(data_extent(figure.axes[i]));
    shared_x.add(extents.back().first);
  }

  const double title_height = figure.title.empty() ? 0.0 : metrics::figure_title_height;
  const double slot = (figure.height - title_height) / static_cast<double>(figure.axes.size());
  std::vector<AxesLayout> layouts;
  for (std::size_t i = 0; i < figure.axes.size(); ++i) {
    const Axes& axes = figure.axes[i];
    const double slot_top = title_height + slot * static_cast<double>(i);
    AxesLayout layout;
    layout.left = metrics::margin_left;
    layout.width = figure.width - metrics::margin_left - metrics::margin_right;
    layout.top = slot_top + (axes.title.empty() ? metrics::gap_top : metrics::axes_title_height);
    const double bottom_space = metrics::tick_label_height + (axes.x_label.empty() ? 0.0 : metrics::axis_label_height);
    layout.height = slot_top + slot - bottom_space - layout.top;
    if (!(layout.height > metrics::minimum_plot_height)) {
      std::ostringstream message;
      message << "figure height " << figure.height << " px leaves no room for " << figure.axes.size() << " axes";
      throw Error(message.str());
    }
    const Extent& x_data = figure.share_x ? shared_x : extents[i].first;
    layout.x_ticks = choose_ticks(axes.x_range, x_data, axes.log_x, "x", i);
    layout.y_ticks = choose_ticks(axes.y_range, extents[i].second, axes.log_y, "y", i, axes.y_step);
    layout.x_scale =
        Scale(layout.x_ticks.range.lo, layout.x_ticks.range.hi, layout.left, layout.left + layout.width, axes.log_x);
    layout.y_scale =
        Scale(layout.y_ticks.range.lo, layout.y_ticks.range.hi, layout.top + layout.height, layout.top, axes.log_y);
    layouts.push_back(layout);
  }
  return layouts;
}

}  // namespace ambid::report
