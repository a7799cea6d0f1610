// `ambid frf`: frequency-domain analysis of a closed-loop experiment — the open-loop plant of
// every OUTPUT/INPUT pair recovered from the closed-loop data, its rational fit (poles, the
// unstable ones kept), the input sensitivity of every loop with its ISO 14839-3 zone. Writes
// DIR/frf.json and SVG Bode / sensitivity plots, prints a short summary.
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/experiment_file.hpp"
#include "core/experiment_io.hpp"
#include "identifier/frf_analysis.hpp"
#include "services/cli/commands.hpp"
#include "services/cli/frf_output.hpp"
#include "services/cli/progress.hpp"
#include "services/report/format.hpp"
#include "services/report/output_lock.hpp"

namespace ambid::cli {
namespace {

struct FrfArguments {
  std::string experiment;
  std::string out;
  ident::FrfAnalysisOptions options;
  bool no_fit = false;
  bool quiet = false;  // no progress line on stderr
};

using report::format_number;

// What the plots and frf.json need beyond the plant: refuse data that cannot give them.
void require_loop_data(const Experiment& e, const std::string& path) {
  if (!e.has_excitation())
    throw InsufficientData(path +
                           ": records no excitation r (signals.r); the plant FRF from closed-loop data needs one");
  if (!e.controller)
    throw InsufficientData(path +
                           ": records no controller; the sensitivity functions (ISO 14839-3) need the "
                           "controller that closed the loop");
}

std::string complex_text(std::complex<double> z) {
  std::string text = format_number(z.real(), 6);
  if (z.imag() != 0.0) text += (z.imag() > 0 ? "+" : "-") + format_number(std::abs(z.imag()), 6) + "j";
  return text;
}

void print_periodic(const ident::PeriodicExcitation& p, const std::vector<std::string>& references) {
  std::cout << "  periodic r (" << (p.source == "r" ? "detected in the record" : "sidecar description, confirmed by r")
            << "): period " << p.period_samples << " samples (" << format_number(p.period_s) << " s), "
            << p.whole_periods << " whole periods, " << p.transient_periods << " discarded as transient, "
            << p.periods_used << " used; " << p.estimator << "\n";
  for (std::size_t c = 0; c < p.lines.size() && c < references.size(); ++c) {
    std::cout << "    " << references[c] << ": " << p.lines[c].size() << " excited lines";
    if (!p.lines[c].empty())
      std::cout << " " << format_number(static_cast<double>(p.lines[c].front()) / p.period_s) << "-"
                << format_number(static_cast<double>(p.lines[c].back()) / p.period_s) << " Hz on a "
                << format_number(1.0 / p.period_s) << " Hz grid";
    std::cout << "\n";
  }
}

void print_summary(const ident::FrfReport& r, const std::string& path, const std::string& out, std::size_t plots,
                   double band_top_hz) {
  std::cout << "ambid frf: " << path << ": " << r.method << " estimate (" << r.excitation << " excitation, " << r.blocks
            << (r.method == "periodic" ? " blocks"
                : r.method == "welch"  ? " segments"
                                       : " steps")
            << "), " << r.frequency_hz.size() << " lines " << format_number(r.frequency_hz(0)) << "-"
            << format_number(r.frequency_hz(r.frequency_hz.size() - 1)) << " Hz\n";
  if (r.periodic) print_periodic(*r.periodic, r.reference_names);
  for (const ident::SensitivityPeak& p : r.sensitivity_peaks)
    std::cout << "  sensitivity " << p.loop << ": peak " << format_number(p.magnitude_db) << " dB at "
              << format_number(p.frequency_hz) << " Hz, ISO 14839-3 zone " << ident::to_string(p.zone) << "\n";
  for (const ident::FittedPair& f : r.fits) {
    const Eigen::VectorXcd poles = f.fit.model.poles();
    std::string in_band, beyond;
    for (Eigen::Index i = 0; i < poles.size(); ++i) {
      if (poles(i).real() <= 0.0) continue;
      (pole_in_band(poles(i), band_top_hz) ? in_band : beyond) += " " + complex_text(poles(i));
    }
    std::cout << "  model " << f.name << ": order " << f.fit.model.numerator_degree() << "/"
              << f.fit.model.denominator_degree()
              << ", unstable poles:" << (in_band.empty() ? " none" : in_band + " rad/s");
    if (!beyond.empty()) std::cout << " (beyond the fitted band, not resolved:" << beyond << ")";
    std::cout << "\n";
  }
  if (r.levels)
    for (const ident::LevelStructuredFit& l : r.levels->levels) {
      std::cout << "  structure at " << r.levels->level_signal << " = "
                << format_number(l.operating_point.at(r.levels->level_signal)) << " (" << l.samples
                << " settled samples):";
      if (!l.fit) std::cout << " no fit: " << l.note;
      for (std::size_t k = 0; l.fit && k < l.fit->derived_names.size(); ++k)
        std::cout << " " << l.fit->derived_names[k] << " " << format_number(l.fit->derived_value(Eigen::Index(k)))
                  << " +- " << format_number(l.fit->derived_sigma(Eigen::Index(k)));
      std::cout << "\n";
    }
  if (r.levels && r.levels->pooled)
    for (std::size_t k = 0; k < r.levels->pooled->derived_names.size(); ++k)
      std::cout << "  structure pooled over " << r.levels->pooled->levels
                << " levels at the operating point: " << r.levels->pooled->derived_names[k] << " "
                << format_number(r.levels->pooled->derived_value(Eigen::Index(k))) << " +- "
                << format_number(r.levels->pooled->derived_sigma(Eigen::Index(k))) << " (Birge ratio "
                << format_number(r.levels->pooled->birge_ratio(Eigen::Index(k))) << ")\n";
  if (r.structured)
    for (std::size_t k = 0; k < r.structured->derived_names.size(); ++k)
      std::cout << "  structure: " << r.structured->derived_names[k] << " "
                << format_number(r.structured->derived_value(Eigen::Index(k))) << " +- "
                << format_number(r.structured->derived_sigma(Eigen::Index(k))) << " (one sigma"
                << (r.levels ? ", at the operating point's level" : "") << ")\n";
  for (const std::string& note : r.notes) std::cout << "  note: " << note << "\n";
  std::cout << "  wrote " << out << "/frf.json and " << plots << " plots\n";
}

}  // namespace

void add_frf_command(CLI::App& app) {
  auto args = std::make_shared<FrfArguments>();
  auto& o = args->options;
  CLI::App* frf = app.add_subcommand("frf", "plant FRFs from closed-loop data, rational fits, ISO 14839-3 sensitivity");
  frf->add_option("experiment", args->experiment, "experiment (.json sidecar, .csv or stem)")->required();
  frf->add_option("--out", args->out, "output directory: frf.json and SVG plots")->required();
  frf->add_option("--f-min", o.f_min, "lowest line kept (Hz)")->capture_default_str();
  frf->add_option("--f-max", o.f_max, "highest line kept (Hz), 0 for all")->capture_default_str();
  frf->add_option("--fit-f-max", o.fit_f_max, "highest line fitted (Hz), 0: 0.1 / sample_time")->capture_default_str();
  frf->add_option("--max-order", o.fit_max_order, "largest denominator degree of the rational fit")
      ->capture_default_str();
  frf->add_option("--confidence", o.confidence, "confidence of the noise bounds")->capture_default_str();
  frf->add_option("--period-tolerance", o.periodicity.tolerance,
                  "r is periodic when it repeats to this fraction of its peak")
      ->capture_default_str();
  frf->add_option("--transient-periods", o.transient_periods,
                  "periodic r: whole periods discarded at the start, -1: one when enough remain")
      ->capture_default_str();
  frf->add_flag("--no-fit", args->no_fit, "skip the rational fits");
  frf->add_flag("--quiet", args->quiet, "no progress line on stderr (there is none when stderr is no terminal)");
  frf->callback([args] {
    const report::OutputLock lock(args->out);
    Progress progress("ambid frf", args->quiet);
    progress.update("read " + args->experiment, 0, 4);
    ReadResult read = read_experiment(args->experiment);
    progress.clear();
    for (const std::string& w : read.warnings) std::cerr << "ambid frf: warning: " << w << "\n";
    const Experiment& e = read.experiment;
    require_loop_data(e, args->experiment);
    args->options.fit = !args->no_fit;
    ident::FrfReport r;
    progress.update(args->no_fit ? "FRF estimate" : "FRF estimate and rational fits", 1, 4);
    try {
      r = ident::analyse_frf(e, args->options);
    } catch (const InsufficientData& error) {  // say which file cannot support an FRF
      throw InsufficientData(args->experiment + ": " + error.what());
    }
    // Every output rendered before any is written, then all replaced together: a failure
    // leaves the previous frf.json and plots as they were.
    progress.update("plots", 2, 4);
    std::vector<std::pair<std::filesystem::path, std::string>> files = frf_plots(r, e, args->options, args->out);
    const std::size_t plots = files.size();
    files.emplace_back(std::filesystem::path(args->out) / "frf.json",
                       frf_json(r, e, args->experiment, args->options).dump(1) + "\n");
    progress.update("write frf.json and plots", 3, 4);
    write_files_atomically(files);
    progress.clear();
    for (const std::string& w : r.warnings) std::cerr << "ambid frf: warning: " << w << "\n";
    print_summary(r, args->experiment, args->out, plots, fit_band_top_hz(e, args->options));
  });
}

}  // namespace ambid::cli
