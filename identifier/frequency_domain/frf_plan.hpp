#pragma once
// Which estimator `analyse_frf` runs, from what the recorded r shows and what the sidecar's
// "excitation" description (written by `ambid sim`, optional) says:
// - r periodic (frf_periodicity.hpp): period-exact analysis at the lines r excites. One
//   reference: exact DFT lines. Several references (excited on different lines, or shifted
//   copies): the plant from a local rational model (degree 4 over 2, 13 lines, no transient
//   terms) of the period-mean outputs on the period-mean inputs, with the noise of the
//   indirect local estimate per period (frf_periodic.hpp).
//   Transient rule: the first whole period is discarded (the loop settles from the switch-on
//   of r), unless FrfAnalysisOptions::transient_periods says otherwise.
// - The description is a hint only. A multisine description whose period r confirms (r
//   repeats at its period, times the Hadamard order for the orthogonal pattern, from sample 0)
//   is used as described (its lines and Hadamard blocks). A description that r contradicts
//   (another period, or periodic where r is not, or the reverse) is ignored with a warning.
// - A stepped sine (one reference, one input) is analysed step by step; anything else by Welch.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/experiment.hpp"
#include "identifier/frequency_domain/frf_periodic.hpp"
#include "identifier/frequency_domain/frf_periodicity.hpp"
#include "identifier/frequency_domain/frf_stepped_sine.hpp"
#include "identifier/frf_analysis.hpp"

namespace ambid::ident {

// The sidecar's "excitation" object, or nullptr.
const nlohmann::json* excitation_description(const Experiment& experiment);
// Its "kind", or "unknown".
std::string excitation_kind(const nlohmann::json* description);

struct PeriodicPlan {
  PeriodicFrfOptions options;
  Eigen::Index end_sample = 0;  // samples [0, end_sample) hold first_sample + whole periods
  PeriodicExcitation summary;   // for the report (periods_used filled after the estimate)
};

// The periodic analysis to run, or nullopt (then notes say why when a periodic analysis was
// expected).
std::optional<PeriodicPlan> plan_periodic(const Experiment& experiment, const Periodicity& detected,
                                          const nlohmann::json* description, const FrfAnalysisOptions& options,
                                          std::vector<std::string>& notes, std::vector<std::string>& warnings);

// The stepped-sine estimator's options from the description, or nullopt (with a note) when
// there is none or the steps cannot be analysed one by one.
std::optional<SteppedSineFrfOptions> plan_stepped_sine(const Experiment& experiment, const nlohmann::json* description,
                                                       const FrfAnalysisOptions& options,
                                                       std::vector<std::string>& notes);

}  // namespace ambid::ident
