#include "services/report/svg.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <utility>

#include "core/error.hpp"
#include "services/report/atomic_file.hpp"

namespace ambid::report {
namespace svg_test {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::string fixed2(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

// Well-formedness by libxml2's parser (scripts/setup.sh installs libxml2-utils).
bool well_formed(const std::string& svg, const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() / ("ambid_svg_test_" + name + ".svg");
  write_file_atomically(path, svg);
  const int status = std::system(("xmllint --noout '" + path.string() + "'").c_str());
  std::filesystem::remove(path);
  return status == 0;
}

Figure figure_of(std::vector<Axes> axes) {
  Figure figure;
  figure.axes = std::move(axes);
  return figure;
}

Axes axes_of(std::vector<Series> series) {
  Axes axes;
  axes.series = std::move(series);
  return axes;
}

Figure bode_like() {
  Axes magnitude =
      axes_of({markers("measured", {1, 10, 100}, {0, -20, -40}), line("fit", {1, 10, 100}, {0.5, -19, -41})});
  magnitude.title = "x/u1";
  magnitude.y_label = "|G| [dB]";
  magnitude.log_x = true;
  Axes phase = axes_of({line("fit", {1, 10, 100}, {-90, -135, -180})});
  phase.x_label = "frequency [Hz]";
  phase.y_label = "phase [deg]";
  phase.log_x = true;
  Figure figure = figure_of({magnitude, phase});
  figure.title = "Bode";
  figure.width = 640;
  figure.height = 480;
  return figure;
}

TEST(Svg, KnownPointLandsAtItsPixel) {
  // Log x over exactly [1, 1000] and y given as [0, 10]: (10, 5) is one third across, halfway up.
  Axes axes = axes_of({line("", {10.0, 1000.0}, {5.0, 10.0})});
  axes.log_x = true;
  axes.x_range = Range{1.0, 1000.0};
  axes.y_range = Range{0.0, 10.0};
  Figure figure = figure_of({axes});
  figure.width = 600;
  figure.height = 400;
  const AxesLayout layout = layout_figure(figure).at(0);
  const double x = layout.left + layout.width / 3.0;
  const double y = layout.top + layout.height / 2.0;
  EXPECT_NEAR(layout.x_scale.to_pixel(10.0), x, 1e-9);
  EXPECT_NEAR(layout.y_scale.to_pixel(5.0), y, 1e-9);
  const std::string svg = render_svg(figure);
  const std::string expected =
      "M" + fixed2(x) + " " + fixed2(y) + "L" + fixed2(layout.left + layout.width) + " " + fixed2(layout.top);
  EXPECT_NE(svg.find("d=\"" + expected + "\""), std::string::npos) << svg;
}

TEST(Svg, StackedAxesShareTheFigureTopToBottom) {
  const auto layouts = layout_figure(bode_like());
  ASSERT_EQ(layouts.size(), 2u);
  EXPECT_LT(layouts[0].top + layouts[0].height, layouts[1].top);
  EXPECT_LE(layouts[1].top + layouts[1].height, 480.0);
  EXPECT_DOUBLE_EQ(layouts[0].x_ticks.range.lo, 1.0);
  EXPECT_DOUBLE_EQ(layouts[0].x_ticks.range.hi, 100.0);
}

TEST(Svg, ShareXUsesTheUnionOfAllAxes) {
  Figure figure = bode_like();
  figure.axes[1].series[0].x = {0.5, 10, 300};
  figure.share_x = true;
  const auto layouts = layout_figure(figure);
  EXPECT_DOUBLE_EQ(layouts[0].x_ticks.range.lo, 0.1);
  EXPECT_DOUBLE_EQ(layouts[0].x_ticks.range.hi, 1000.0);
  EXPECT_DOUBLE_EQ(layouts[1].x_ticks.range.hi, 1000.0);
}

TEST(Svg, OutputIsWellFormedXmlWithLegendTitlesAndMarkers) {
  Figure figure = bode_like();
  ReferenceLine limit;
  limit.value = -30;
  limit.label = "limit";
  figure.axes[0].reference_lines = {limit};
  const std::string svg = render_svg(figure);
  EXPECT_TRUE(well_formed(svg, "bode"));
  EXPECT_NE(svg.find(">measured</text>"), std::string::npos);
  EXPECT_NE(svg.find(">frequency [Hz]</text>"), std::string::npos);
  EXPECT_NE(svg.find(">limit</text>"), std::string::npos);
  EXPECT_NE(svg.find("<circle"), std::string::npos);
  EXPECT_NE(svg.find(">100</text>"), std::string::npos);   // the last decade tick
  EXPECT_EQ(svg.find(">1000</text>"), std::string::npos);  // x range is [1, 100]
}

TEST(Svg, LabelsAreEscaped) {
  Figure figure = bode_like();
  figure.title = "R1 <drift> & \"hot\" 'coil'";
  figure.axes[0].series[0].label = "a<b";
  const std::string svg = render_svg(figure);
  EXPECT_NE(svg.find("R1 &lt;drift&gt; &amp; &quot;hot&quot; &apos;coil&apos;"), std::string::npos);
  EXPECT_NE(svg.find(">a&lt;b</text>"), std::string::npos);
  EXPECT_EQ(svg.find("<drift>"), std::string::npos);
  EXPECT_TRUE(well_formed(svg, "escaped"));
}

TEST(Svg, NanAndNonPositiveOnLogAxisBreakTheLine) {
  Axes axes = axes_of({line("", {0, 1, 2, 3, 4, 5}, {1, 2, nan, 4, -1, 6})});
  axes.log_y = true;
  const std::string svg = render_svg(figure_of({axes}));
  const std::regex path_d("class=\"series\" d=\"([^\"]*)\"");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(svg, match, path_d));
  const std::string d = match[1];
  EXPECT_EQ(std::count(d.begin(), d.end(), 'M'), 3);  // pieces {0,1}, {3}, {5}
  EXPECT_EQ(std::count(d.begin(), d.end(), 'L'), 1);
  EXPECT_EQ(d.find("nan"), std::string::npos);
}

TEST(Svg, RejectsWhatCannotBeDrawn) {
  EXPECT_THROW(render_svg(Figure{}), Error);
  EXPECT_THROW(render_svg(figure_of({axes_of({line("bad", {1, 2}, {1})})})), Error);
  EXPECT_THROW(render_svg(figure_of({axes_of({line("", {nan, nan}, {1, 2})})})), Error);
  const Axes fine = axes_of({line("", {1, 2}, {1, 2})});
  Figure too_small = figure_of({fine, fine});
  too_small.height = 10;
  EXPECT_THROW(render_svg(too_small), Error);
}

TEST(AtomicFile, WritesCreatesDirectoriesAndReplaces) {
  const auto directory = std::filesystem::temp_directory_path() / "ambid_atomic_file_test";
  std::filesystem::remove_all(directory);
  const auto path = directory / "sub" / "plot.svg";
  write_file_atomically(path, "first");
  write_file_atomically(path, "second");
  std::ifstream in(path);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "second");
  EXPECT_EQ(
      std::distance(std::filesystem::directory_iterator(path.parent_path()), std::filesystem::directory_iterator()),
      1);  // no temporary left behind
  EXPECT_THROW(write_file_atomically(path / "below-a-file", "x"), Error);
  std::filesystem::remove_all(directory);
}

}  // namespace svg_test
}  // namespace ambid::report
