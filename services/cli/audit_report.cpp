#include "services/cli/audit_report.hpp"

#include <cmath>
#include <sstream>

#include "diagnostics/plant_families.hpp"
#include "services/report/figure.hpp"
#include "services/report/svg.hpp"
#include "services/report/xml_escape.hpp"

namespace ambid::cli {
namespace {

// The SVG element without the XML declaration, to sit inside the HTML page.
std::string inline_svg(const report::Figure& figure) {
  const std::string svg = report::render_svg(figure);
  return svg.substr(svg.find("<svg"));
}

std::vector<double> to_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

// At most ~2000 points per trace: every k-th sample of the validation segment's first 0.2 s.
report::Figure time_traces(const diag::AuditResult& r) {
  report::Figure fig;
  fig.title = "Validation segment: measured and replayed outputs (deviations)";
  fig.height = 250.0 * double(r.outputs.size());
  fig.share_x = true;
  const Eigen::Index begin = r.validation.begin;
  const Eigen::Index n = std::min<Eigen::Index>(r.validation.size(), 2000);
  for (std::size_t j = 0; j < r.outputs.size(); ++j) {
    const auto col = Eigen::Index(j);
    report::Axes ax;
    ax.y_label = r.outputs[j];
    ax.x_label = j + 1 == r.outputs.size() ? "t [s]" : "";
    const std::vector<double> t = to_vector(r.t.segment(begin, n));
    ax.series = {report::line("measured", t, to_vector(r.measured.col(col).segment(begin, n))),
                 report::line("nominal model", t, to_vector(r.nominal.col(col).segment(begin, n)))};
    if (!r.extended_effects.empty())
      ax.series.push_back(report::line("extended model", t, to_vector(r.extended.col(col).segment(begin, n))));
    ax.series[1].style.dash = "6 3";
    fig.axes.push_back(ax);
  }
  return fig;
}

report::Figure residual_spectra(const diag::AuditResult& r) {
  report::Figure fig;
  fig.title = "Residual spectra (measured minus model), validation segment";
  fig.height = 250.0 * double(r.outputs.size());
  fig.share_x = true;
  const Eigen::Index bins = r.residual_nominal.frequency.size();
  const std::vector<double> f = to_vector(r.residual_nominal.frequency.tail(bins - 1));
  for (std::size_t j = 0; j < r.outputs.size(); ++j) {
    const auto col = Eigen::Index(j);
    report::Axes ax;
    ax.log_x = ax.log_y = true;
    ax.y_label = "PSD " + r.outputs[j];
    ax.x_label = j + 1 == r.outputs.size() ? "f [Hz]" : "";
    ax.series = {report::line("nominal residual", f, to_vector(r.residual_nominal.power.col(col).tail(bins - 1)))};
    if (!r.extended_effects.empty())
      ax.series.push_back(
          report::line("extended residual", f, to_vector(r.residual_extended.power.col(col).tail(bins - 1))));
    fig.axes.push_back(ax);
  }
  return fig;
}

std::vector<double> decibels(const Eigen::VectorXcd& g) {
  std::vector<double> db;
  for (const auto& v : g) db.push_back(20 * std::log10(std::abs(v)));
  return db;
}
std::vector<double> degrees(const Eigen::VectorXcd& g) {
  std::vector<double> deg;
  for (const auto& v : g) deg.push_back(std::arg(v) * 180.0 / 3.141592653589793);
  return deg;
}

// Magnitude and phase of element (i, j) of the measured FRF (markers) and of the models.
report::Figure bode(const std::string& title, const std::string& label, const ident::Frf& measured,
                    const ident::Frf& nominal, const ident::Frf& extended, bool with_extended, Eigen::Index i,
                    Eigen::Index j) {
  report::Figure fig;
  fig.title = title;
  fig.share_x = true;
  report::Axes magnitude, phase;
  magnitude.log_x = phase.log_x = true;
  magnitude.y_label = "|" + label + "| [dB]";
  phase.y_label = "phase [deg]";
  phase.x_label = "f [Hz]";
  auto add = [&](const ident::Frf& frf, const std::string& name, bool as_markers) {
    if (frf.lines() == 0) return;
    const Eigen::VectorXcd g = frf.element(i, j);
    const std::vector<double> f = to_vector(frf.frequency_hz);
    magnitude.series.push_back(as_markers ? report::markers(name, f, decibels(g)) : report::line(name, f, decibels(g)));
    phase.series.push_back(as_markers ? report::markers(name, f, degrees(g)) : report::line(name, f, degrees(g)));
  };
  add(measured, "measured", true);
  add(nominal, "nominal model", false);
  if (with_extended) add(extended, "extended model", false);
  fig.axes = {magnitude, phase};
  return fig;
}

// measured / model for every plant pair: 0 dB and 0 deg where the model is right.
report::Figure ratio_plot(const diag::AuditResult& r, const std::vector<std::string>& inputs) {
  report::Figure fig;
  fig.title = "Measured / nominal model plant FRF per output/input pair (well-determined lines)";
  fig.share_x = true;
  report::Axes magnitude, phase;
  magnitude.log_x = phase.log_x = true;
  magnitude.y_label = "|ratio| [dB]";
  phase.y_label = "phase [deg]";
  phase.x_label = "f [Hz]";
  const ident::Frf& q = r.frfs.ratio_nominal;
  for (Eigen::Index i = 0; i < q.rows(); ++i)
    for (Eigen::Index j = 0; j < q.cols(); ++j) {
      const std::vector<Eigen::Index> lines = diag::determined_lines(r.frfs, i, j);
      if (lines.size() < 2) continue;
      std::vector<double> f;
      Eigen::VectorXcd g(Eigen::Index(lines.size()));
      for (std::size_t k = 0; k < lines.size(); ++k) {
        f.push_back(q.frequency_hz[lines[k]]);
        g[Eigen::Index(k)] = q.value[std::size_t(lines[k])](i, j);
      }
      const std::string name = r.outputs[std::size_t(i)] + "/" + inputs[std::size_t(j)];
      magnitude.series.push_back(report::markers(name, f, decibels(g)));
      phase.series.push_back(report::markers(name, f, degrees(g)));
    }
  fig.axes = {magnitude, phase};
  return fig;
}

// Per part of the record: the level of the model error, log|G_meas / G_nominal|, per pair.
std::string amplitude_table(const diag::AuditResult& r) {
  using report::xml_escape;
  const auto& a = r.amplitude;
  std::ostringstream h;
  h.precision(3);
  h << "<h2>Dependence on amplitude</h2>\n";
  if (!a.determinable) {
    h << "<p>Not determinable: " << xml_escape(a.reason) << ".</p>\n";
    return h.str();
  }
  h << "<p>Median log|G_meas / G_nominal| over the excited lines, per contiguous part of the record: the same in "
       "every part for a linear model error, changing with the excitation amplitude for a nonlinear one. "
    << (a.dependent ? "<b>The error depends on the amplitude</b>" : "No amplitude dependence") << " (max |z| "
    << a.max_abs_z << " between the parts of highest and lowest excitation).</p>\n"
    << "<table><tr><th>part</th><th>excitation rms</th>";
  for (const auto& y : r.outputs)
    for (const auto& u : r.inputs) h << "<th>" << xml_escape(y + "/" + u) << "</th>";
  h << "</tr>\n";
  for (const auto& p : a.parts) {
    h << "<tr><td>" << p.samples.begin << "&ndash;" << p.samples.end << "</td><td>" << p.excitation_rms << "</td>";
    for (Eigen::Index i = 0; i < p.log_ratio.rows(); ++i)
      for (Eigen::Index j = 0; j < p.log_ratio.cols(); ++j)
        h << "<td>" << p.log_ratio(i, j) << " &plusmn; " << p.log_ratio_se(i, j) << "</td>";
    h << "</tr>\n";
  }
  h << "</table>\n";
  return h.str();
}

}  // namespace

std::string audit_verdict(const diag::AuditResult& r) {
  std::ostringstream s;
  s.precision(3);
  if (r.cause == "none") {
    s << "The nominal model explains this record as well as any single effect of the catalogue: no extension "
         "reduces the validation error (NRMSE "
      << r.baseline_total << ") by more than noise explains (z above " << r.z_threshold
      << ", i.e. a false-acceptance probability of " << r.false_acceptance << "). Cause: none.";
    return s.str();
  }
  if (r.cause == "unexplained") {
    s << "The nominal model is wrong (its validation residual is more than noise), but no extension of the catalogue "
         "leaves a residual consistent with noise (residual check at "
      << r.residual_alpha << "). Cause: unexplained.";
    if (!r.findings.empty())
      s << " The best candidate was " << r.findings.front().effect.name << " (NRMSE " << r.baseline_total << " -> "
        << r.findings.front().nrmse_total_after << ").";
    if (r.amplitude.dependent) s << " The nominal model's error grows with the excitation amplitude.";
    return s.str();
  }
  for (const auto& f : r.findings) {
    if (!f.accepted) continue;
    s << (f.round == 1 ? "The simulation misses " : " Besides, it misses ") << f.effect.name;
    if (f.effect.channel) s << " on channel " << f.effect.channel;
    const sim::EffectSpec& spec = sim::effect_spec(diag::effect_catalogue_of(r.plant_model, "audit"), f.effect.name);
    s << " (" << spec.summary << "). With it fitted (";
    bool first = true;
    for (const auto& p : spec.parameters) {
      s << (first ? "" : ", ") << p.name << " = " << f.effect.at(p.name) << " " << p.unit;
      first = false;
    }
    s << "), the error on data the fit did not see falls from NRMSE " << f.nrmse_total_before << " to "
      << f.nrmse_total_after << "; noise alone would explain such a gain with probability ";
    if (f.test.p_value < 1e-6)
      s << "below 1e-6";
    else
      s << f.test.p_value;
    s << " (z = " << f.test.z << ").";
  }
  if (r.amplitude.dependent) s << " The nominal model's error grows with the excitation amplitude: a nonlinear effect.";
  return s.str();
}

std::string audit_report_html(const diag::AuditResult& r, const std::string& experiment_name) {
  using report::xml_escape;
  std::ostringstream h;
  h.precision(4);
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>ambid audit: "
    << xml_escape(experiment_name) << "</title>\n<style>body{font-family:sans-serif;margin:2em;max-width:70em}"
    << "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:0.3em 0.6em;text-align:left}"
    << ".verdict{font-size:1.2em;background:#eef;padding:1em}</style></head><body>\n";
  h << "<h1>Model audit: " << xml_escape(experiment_name) << "</h1>\n";
  h << "<p class=\"verdict\">" << xml_escape(audit_verdict(r)) << "</p>\n";
  h << "<p>Estimation samples " << r.estimation.begin << "&ndash;" << r.estimation.end << ", validation samples "
    << r.validation.begin << "&ndash;" << r.validation.end << ". NRMSE = ||y_meas - y_model|| / ||y_meas - mean||"
    << " on the validation segment, the model replayed in closed loop with the recorded controller and r.</p>\n";
  h << "<h2>Nominal model</h2>\n<table><tr><th>output</th><th>NRMSE</th><th>max |corr(residual, r)|</th></tr>\n";
  for (std::size_t j = 0; j < r.outputs.size(); ++j)
    h << "<tr><td>" << xml_escape(r.outputs[j]) << "</td><td>" << r.baseline_nrmse[Eigen::Index(j)] << "</td><td>"
      << r.excitation_correlation.row(Eigen::Index(j)).maxCoeff() << "</td></tr>\n";
  h << "<tr><td>total (mean)</td><td>" << r.baseline_total << "</td><td></td></tr></table>\n";
  h << "<h2>Candidate extensions (fitted, best first)</h2>\n<table><tr><th>effect</th><th>channel</th>"
    << "<th>parameters</th><th>NRMSE after</th><th>z (noise: N(0,1))</th><th>accepted</th><th>evidence</th></tr>\n";
  for (const auto& f : r.findings) {
    h << "<tr><td>" << f.effect.name << "</td><td>" << (f.effect.channel ? std::to_string(f.effect.channel) : "&ndash;")
      << "</td><td>";
    for (const auto& p : sim::effect_spec(diag::effect_catalogue_of(r.plant_model, "audit"), f.effect.name).parameters)
      h << xml_escape(p.name) << " = " << f.effect.at(p.name) << " " << xml_escape(p.unit) << "<br>";
    h << "</td><td>" << f.nrmse_total_after << "</td><td>" << f.test.z << "</td><td>" << (f.accepted ? "yes" : "no")
      << "</td><td>" << xml_escape(f.evidence) << "</td></tr>\n";
  }
  h << "</table>\n<p>A finding is accepted when its validation improvement z exceeds " << r.z_threshold
    << ": the probability that noise alone gets there for the best of " << r.findings.size() << " fitted candidates is "
    << r.false_acceptance << ".</p>\n";
  h << amplitude_table(r);
  h << "<h2>Time traces</h2>\n" << inline_svg(time_traces(r));
  h << "\n<h2>Residual spectra</h2>\n" << inline_svg(residual_spectra(r));
  const bool extended = !r.extended_effects.empty();
  if (r.frfs.loop_measured.lines() > 0) {
    h << "\n<h2>Closed-loop frequency response</h2>\n"
      << inline_svg(bode("Closed loop " + r.outputs.front() + "/r1: measured, nominal and extended model",
                         r.outputs.front() + "/r1", r.frfs.loop_measured, r.frfs.loop_nominal, r.frfs.loop_extended,
                         extended, 0, 0));
  }
  if (r.frfs.measured.lines() > 0) {
    h << "\n<h2>Plant frequency response (indirect closed-loop estimate)</h2>\n<p>G = S_yr S_ur<sup>+</sup> of the "
         "measurement and of each replayed model, on the lines where the inputs are coherent with the excitation.</p>\n"
      << inline_svg(
             bode("Plant " + r.outputs.front() + "/" + r.inputs.front() + ": measured, nominal and extended model",
                  r.outputs.front() + "/" + r.inputs.front(), r.frfs.measured, r.frfs.nominal, r.frfs.extended,
                  extended, 0, 0))
      << "\n<h2>Measured / model frequency response ratio</h2>\n"
      << inline_svg(ratio_plot(r, r.inputs));
  } else {
    h << "\n<p>The validation segment is too short (or not excited enough) for frequency responses.</p>";
  }
  h << "\n</body></html>\n";
  return h.str();
}

}  // namespace ambid::cli
