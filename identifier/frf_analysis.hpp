#pragma once
// `ambid frf`: the frequency-domain analysis of one closed-loop experiment, values only (the
// command line writes files and plots). What it does:
// - chooses the estimator from the recorded r (frequency_domain/frf_plan.hpp): a periodic r
//   (multisine, repeated PRBS, from any generator) is analysed period-exactly at the lines it
//   excites, the sidecar's "excitation" description serving as a hint only (Hadamard blocks
//   of `ambid sim`'s multisine); a stepped sine with one reference and one plant input step by
//   step (exact DFT of each measurement window); anything else by Welch cross spectra;
// - the plant FRF of every OUTPUT/INPUT pair (indirect, with noise bounds or coherence), the
//   direct estimate for comparison, the closed-loop responses;
// - with a recorded controller: the input sensitivity measured from r -> u, its peak per plant
//   input and of sigma_max with the ISO 14839-3 zone, and the seed 003 eq. 5 controller check;
// - a continuous rational fit of every pair below fit_f_max (order by validation misfit, ZOH
//   compensated, noise weighted when variances exist): poles, zeros, gain;
// - where the plant family has a linear structure, that structure fitted to the plant FRF and
//   what it derives (the maglev's unstable pole), with one-sigma uncertainties; level by level
//   on records of reference steps where the family's linearisation changes with the level.
// Steps that cannot run say why in `notes` instead of failing the whole analysis.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "identifier/frequency_domain/frf_levels.hpp"
#include "identifier/frequency_domain/frf_open_loop.hpp"
#include "identifier/frequency_domain/frf_periodicity.hpp"
#include "identifier/frequency_domain/frf_structured.hpp"
#include "identifier/frequency_domain/rational_fit.hpp"
#include "identifier/frequency_domain/sensitivity_function.hpp"
#include "identifier/frf_types.hpp"
#include "identifier/iso_14839.hpp"

namespace ambid::ident {

struct FrfAnalysisOptions {
  int transient_periods = -1;        // periodic: discarded periods; -1: one if a block remains, else 0
  PeriodicityOptions periodicity;    // how a periodic r is recognised
  Eigen::Index segment_samples = 0;  // Welch window; 0: largest power of two <= samples / 8 (>= 64)
  double f_min = 0.0, f_max = 0.0;   // lines kept (0: all)
  double confidence = 0.95;          // of the noise bounds
  bool fit = true;
  double fit_f_max = 0.0;  // 0: min(highest line, 0.1 / sample_time)
  int fit_max_order = 6;
  IsoZoneLimits iso;
};

struct PlantPair {
  std::string name;  // "OUTPUT/INPUT", e.g. "x/u1"
  std::string output, input;
  Eigen::VectorXcd value;     // per line
  Eigen::VectorXd variance;   // E|error|^2 per line; empty when unknown
  Eigen::VectorXd bound;      // |G - value| <= bound at options.confidence; empty when unknown
  Eigen::VectorXd coherence;  // Welch: multiple coherence of the output with the references
};

struct FittedPair {
  std::string name, output, input;
  RationalFit fit;
};

// The periodic analysis that ran.
struct PeriodicExcitation {
  std::string source;     // "r": detected in the record; "sidecar": its description, confirmed by r
  std::string estimator;  // "exact lines" | "local polynomial" (Hadamard blocks) | "local rational" (zippered)
  Eigen::Index period_samples = 0;
  double period_s = 0.0;
  Eigen::Index first_sample = 0;       // where the first whole period starts
  Eigen::Index whole_periods = 0;      // recorded
  Eigen::Index transient_periods = 0;  // discarded at the start
  Eigen::Index periods_per_block = 1;
  Eigen::Index periods_used = 0;
  std::vector<std::vector<Eigen::Index>> lines;  // excited DFT lines of one period, per reference
};

struct FrfReport {
  std::string method;      // "periodic" | "stepped_sine" | "welch"
  std::string excitation;  // the sidecar's excitation kind, or "unknown"
  std::vector<std::string> output_names, input_names, reference_names;
  Eigen::VectorXd frequency_hz;
  Frf plant, plant_direct, output_from_reference, input_from_reference;
  std::vector<PlantPair> pairs;                    // outputs x inputs, output-major
  Eigen::Index blocks = 0;                         // periodic: blocks averaged; stepped sine: steps; Welch: segments
  std::optional<Frf> sensitivity;                  // input sensitivity S_u
  std::vector<SensitivityPeak> sensitivity_peaks;  // one per plant input, then "sigma_max"
  std::optional<ControllerCheck> controller_check;
  std::vector<FittedPair> fits;
  // The family's physical structure fitted to the plant FRF (plant_families.hpp
  // `frf_structure`; the maglev's unstable pole with its sigma); empty for a family without.
  // For a family whose structure changes with the level (FrfStructure::level_signal): the
  // structure per settled level (frf_levels.hpp), and `structured` is the level at the
  // record's operating point (empty, with a note, when no level lies there).
  std::optional<StructuredFrfFit> structured;
  std::optional<LevelStructuredAnalysis> levels;
  std::optional<PeriodicExcitation> periodic;  // method "periodic": what was detected and used
  // Samples where a controller clamp acted (controller.output_limits, state_limits): not
  // exogenous, so no block (periodic: period, and the one after it; Welch: segment) holding
  // one is averaged. blocks_left_out counts those blocks.
  Eigen::Index clamped_samples = 0, blocks_left_out = 0;
  std::vector<std::string> notes;
  std::vector<std::string> warnings;  // e.g. a sidecar description that the recorded r contradicts
};

// Throws Error for an invalid experiment and InsufficientData when it has no excitation or the
// estimator cannot produce a plant FRF (too short, references not independent).
FrfReport analyse_frf(const Experiment& experiment, const FrfAnalysisOptions& options = {});

}  // namespace ambid::ident
