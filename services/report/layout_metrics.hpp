#pragma once
// Fixed sizes (px) of the parts around a plot area; shared by layout and drawing.
namespace ambid::report::metrics {

inline constexpr double margin_left = 72.0;
inline constexpr double margin_right = 24.0;
inline constexpr double figure_title_height = 30.0;
inline constexpr double axes_title_height = 26.0;
inline constexpr double gap_top = 12.0;
inline constexpr double tick_label_height = 24.0;
inline constexpr double axis_label_height = 18.0;
inline constexpr double minimum_plot_height = 20.0;
inline constexpr double font_size = 12.0;
inline constexpr double legend_row_height = 16.0;
inline constexpr double char_width = 6.8;  // rough average for the legend box width

}  // namespace ambid::report::metrics
