// The SVG plots of `ambid frf`.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "core/linalg.hpp"
#include "identifier/iso_14839.hpp"
#include "services/cli/frf_output.hpp"
#include "services/report/format.hpp"
#include "services/report/svg.hpp"

namespace ambid::cli {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

std::vector<double> std_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

std::vector<double> db(const Eigen::VectorXcd& v) {
  std::vector<double> out;
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(20.0 * std::log10(std::abs(v(i))));
  return out;
}

// Phase in degrees within (-180, 180]; for a line, NaN is put where the phase wraps so that the
// plot shows a gap instead of a vertical jump.
void wrapped_phase(const Eigen::VectorXcd& v, const std::vector<double>& f, bool line_gaps, std::vector<double>& x,
                   std::vector<double>& y) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    const double phase = std::arg(v(i)) * 180.0 / std::numbers::pi;
    if (line_gaps && !y.empty() && std::abs(phase - y.back()) > 180.0) {
      x.push_back(kNan);
      y.push_back(kNan);
    }
    x.push_back(f[static_cast<std::size_t>(i)]);
    y.push_back(phase);
  }
}

// The fitted continuous model seen through the zero-order hold, as the sampled data are
// (the fit removed the same factor from the data: identifier/rational_fit.hpp).
Eigen::VectorXcd model_response(const ident::RationalModel& model, const Eigen::VectorXd& f, double T) {
  Eigen::VectorXcd out(f.size());
  for (Eigen::Index i = 0; i < f.size(); ++i) {
    const double w = 2.0 * std::numbers::pi * f(i);
    const std::complex<double> jwT(0.0, w * T);
    out(i) = model.response(w) * (1.0 - std::exp(-jwT)) / jwT;
  }
  return out;
}

Eigen::VectorXd log_grid(double lo, double hi, Eigen::Index points) {
  Eigen::VectorXd f(points);
  for (Eigen::Index i = 0; i < points; ++i)
    f(i) = lo * std::pow(hi / lo, static_cast<double>(i) / static_cast<double>(points - 1));
  return f;
}

std::string file_safe(const std::string& name) {
  std::string out;
  for (const char c : name) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' ? c : '_';
  return out;
}

report::Axes bode_axes(const std::string& y_label, bool bottom) {
  report::Axes axes;
  axes.y_label = y_label;
  axes.log_x = true;
  if (bottom) axes.x_label = "frequency [Hz]";
  return axes;
}

report::Figure bode_figure(const ident::PlantPair& pair, const ident::FittedPair* fitted,
                           const ident::FrfReport& report, const Experiment& experiment,
                           const ident::FrfAnalysisOptions& options) {
  const std::vector<double> f = std_vector(report.frequency_hz);
  report::Axes magnitude = bode_axes("|" + pair.name + "| [dB SI]", false);
  report::Axes phase = bode_axes("phase [deg]", !pair.coherence.size());
  magnitude.series.push_back(report::markers("measured (" + report.method + ")", f, db(pair.value)));
  magnitude.series.back().style.marker_size = 1.8;
  std::vector<double> phase_x, phase_y;
  wrapped_phase(pair.value, f, false, phase_x, phase_y);
  phase.series.push_back(report::markers("measured", phase_x, phase_y));
  phase.series.back().style.marker_size = 1.8;
  if (fitted != nullptr) {
    const double top = std::min(fit_band_top_hz(experiment, options), report.frequency_hz.maxCoeff());
    const Eigen::VectorXd grid = log_grid(report.frequency_hz(0), top, 400);
    const Eigen::VectorXcd g = model_response(fitted->fit.model, grid, experiment.sample_time);
    const std::string label = "model (" + std::to_string(fitted->fit.model.numerator_degree()) + "/" +
                              std::to_string(fitted->fit.model.denominator_degree()) + ")";
    magnitude.series.push_back(report::line(label, std_vector(grid), db(g)));
    std::vector<double> model_x, model_y;
    wrapped_phase(g, std_vector(grid), true, model_x, model_y);
    phase.series.push_back(report::line(label, model_x, model_y));
  }
  if (pair.bound.size() > 0) {
    const int percent = static_cast<int>(std::lround(100.0 * options.confidence));
    magnitude.series.push_back(
        report::line(std::to_string(percent) + " % noise bound", f, db(pair.bound.cast<std::complex<double>>())));
    magnitude.series.back().style.color = "#999999";
    magnitude.series.back().style.line_width = 1.0;
  }
  phase.y_range = report::Range{-180.0, 180.0};
  phase.y_step = 90.0;
  // The measured magnitude decides the view (a noise bound far below it is cut off).
  const std::vector<double> measured_db = magnitude.series.front().y;
  const auto [lo, hi] = std::minmax_element(measured_db.begin(), measured_db.end());
  magnitude.y_range = report::Range{10.0 * std::floor(*lo / 10.0) - 20.0, 10.0 * std::ceil(*hi / 10.0) + 10.0};
  report::Figure figure;
  figure.title = pair.name + " (" + experiment.name + ")";
  figure.height = pair.coherence.size() ? 720.0 : 600.0;
  figure.share_x = true;
  figure.axes = {magnitude, phase};
  if (pair.coherence.size() > 0) {
    report::Axes coherence = bode_axes("coherence", true);
    coherence.series.push_back(report::line("multiple coherence of " + pair.output, f, std_vector(pair.coherence)));
    coherence.y_range = report::Range{0.0, 1.0};
    figure.axes.push_back(coherence);
  }
  return figure;
}

report::ReferenceLine limit(double value, const std::string& label) {
  report::ReferenceLine line;
  line.value = value;
  line.label = label + " " + report::format_number(value) + " dB";
  return line;
}

report::Figure sensitivity_figure(const std::string& loop, const Eigen::VectorXd& magnitude,
                                  const ident::SensitivityPeak& peak, const ident::FrfReport& report,
                                  const ident::FrfAnalysisOptions& options) {
  report::Axes axes = bode_axes("|S| [dB]", true);
  std::vector<double> m_db;
  for (Eigen::Index i = 0; i < magnitude.size(); ++i) m_db.push_back(ident::magnitude_db(magnitude(i)));
  axes.series.push_back(report::line(loop == "sigma_max" ? "largest singular value of S_u" : "S_u " + loop + "," + loop,
                                     std_vector(report.frequency_hz), m_db));
  axes.series.push_back(report::markers("peak", {peak.frequency_hz}, {peak.magnitude_db}, report::Marker::cross));
  axes.series.back().style.marker_size = 5.0;
  axes.reference_lines = {limit(options.iso.ab_db, "A/B"), limit(options.iso.bc_db, "B/C"),
                          limit(options.iso.cd_db, "C/D")};
  report::Figure figure;
  figure.title = "input sensitivity " + loop + ": peak " + report::format_number(peak.magnitude_db) + " dB at " +
                 report::format_number(peak.frequency_hz) + " Hz, ISO 14839-3 zone " + ident::to_string(peak.zone);
  figure.height = 420.0;
  figure.axes = {axes};
  return figure;
}

}  // namespace

std::vector<std::pair<std::filesystem::path, std::string>> frf_plots(const ident::FrfReport& report,
                                                                     const Experiment& experiment,
                                                                     const ident::FrfAnalysisOptions& options,
                                                                     const std::filesystem::path& directory) {
  std::vector<std::pair<std::filesystem::path, std::string>> written;
  const auto write = [&](const std::string& name, const report::Figure& figure) {
    written.emplace_back(directory / name, report::render_svg(figure));
  };
  for (const ident::PlantPair& pair : report.pairs) {
    const ident::FittedPair* fitted = nullptr;
    for (const ident::FittedPair& f : report.fits)
      if (f.name == pair.name) fitted = &f;
    write("bode_" + file_safe(pair.output) + "_" + file_safe(pair.input) + ".svg",
          bode_figure(pair, fitted, report, experiment, options));
  }
  if (!report.sensitivity) return written;
  const ident::Frf& S = *report.sensitivity;
  for (const ident::SensitivityPeak& peak : report.sensitivity_peaks) {
    Eigen::VectorXd magnitude(S.lines());
    for (Eigen::Index l = 0; l < S.lines(); ++l) {
      const Eigen::MatrixXcd& s = S.value[static_cast<std::size_t>(l)];
      if (peak.loop == "sigma_max") {
        magnitude(l) = linalg::singular_values(s)(0);
      } else {
        const auto it = std::find(experiment.u_names.begin(), experiment.u_names.end(), peak.loop);
        const auto i = static_cast<Eigen::Index>(it - experiment.u_names.begin());
        magnitude(l) = std::abs(s(i, i));
      }
    }
    write("sensitivity_" + file_safe(peak.loop) + ".svg",
          sensitivity_figure(peak.loop, magnitude, peak, report, options));
  }
  return written;
}

}  // namespace ambid::cli
