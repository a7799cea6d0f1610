// report: draw a figure with two series and write it as an SVG file, atomically.
//   plot_report OUT.svg
#include <cmath>
#include <iostream>

#include "services/report/atomic_file.hpp"
#include "services/report/figure.hpp"
#include "services/report/svg.hpp"

int main(int argc, char** argv) try {
  if (argc != 2) {
    std::cerr << "usage: plot_report OUT.svg\n";
    return 2;
  }
  std::vector<double> f, magnitude, phase;
  for (double hz = 1.0; hz <= 1000.0; hz *= 1.1) {  // a first-order lag with its corner at 50 Hz
    f.push_back(hz);
    magnitude.push_back(-10.0 * std::log10(1.0 + (hz / 50.0) * (hz / 50.0)));
    phase.push_back(-std::atan(hz / 50.0) * 180.0 / M_PI);
  }
  ambid::report::Figure figure;
  figure.title = "First-order lag";
  figure.share_x = true;
  ambid::report::Axes bode_magnitude, bode_phase;
  bode_magnitude.y_label = "magnitude (dB)";
  bode_phase.x_label = "frequency (Hz)";
  bode_phase.y_label = "phase (deg)";
  bode_magnitude.log_x = bode_phase.log_x = true;
  bode_magnitude.series = {ambid::report::line("|G|", f, magnitude)};
  bode_phase.series = {ambid::report::line("arg G", f, phase)};
  figure.axes = {bode_magnitude, bode_phase};
  ambid::report::write_file_atomically(argv[1], ambid::report::render_svg(figure));
  std::cout << "wrote " << argv[1] << "\n";
} catch (const std::exception& error) {  // ambid::Error, or a file that cannot be written
  std::cerr << "plot_report: " << error.what() << "\n";
  return 1;
}
