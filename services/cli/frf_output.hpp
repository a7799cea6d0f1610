#pragma once
// What `ambid frf` writes besides its summary: DIR/frf.json (the values) and the SVG plots
// (Bode plots of measured versus fitted model per plant pair, sensitivity per loop).
#include <complex>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/experiment.hpp"
#include "identifier/frf_analysis.hpp"

namespace ambid::cli {

// The fit band of the analysis (what analyse_frf fits: lines up to options.fit_f_max, or
// 0.1 / sample_time when that is 0).
double fit_band_top_hz(const Experiment& experiment, const ident::FrfAnalysisOptions& options);

// A pole beyond the fitted band (|p| > 2 pi top_hz) is not resolved by the data: an order
// selection artefact as likely as a real pole, so summaries list such poles apart.
bool pole_in_band(std::complex<double> pole, double top_hz);

// frf.json: frequency_hz, plant (per "OUTPUT/INPUT": re, im, noise_std and bound, or
// coherence), plant_direct, sensitivity (per loop: peak_db, peak_hz, zone), model (per pair:
// poles and zeros as [re, im] in rad/s, gain, degrees, misfit), controller_check, periodic
// (what a periodic analysis detected: period, whole and used periods, lines per reference),
// notes, warnings.
nlohmann::json frf_json(const ident::FrfReport& report, const Experiment& experiment,
                        const std::string& experiment_path, const ident::FrfAnalysisOptions& options);

// One bode_OUTPUT_INPUT.svg per pair and one sensitivity_LOOP.svg per loop, rendered: each
// file's path in `directory` with its content, for core's write_files_atomically.
std::vector<std::pair<std::filesystem::path, std::string>> frf_plots(const ident::FrfReport& report,
                                                                     const Experiment& experiment,
                                                                     const ident::FrfAnalysisOptions& options,
                                                                     const std::filesystem::path& directory);

}  // namespace ambid::cli
