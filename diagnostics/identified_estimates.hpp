#pragma once
// The estimate window of one identification: the monitored physical parameters of its plant
// family (monitored_parameters, plant_families.hpp) with the one-sigma uncertainty the
// identifier reports for each.
#include <map>
#include <string>

#include "diagnostics/estimate.hpp"
#include "identifier/identify_window.hpp"

namespace ambid::diag {

// From the physical values and their uncertainties (the `physical` and `uncertainty` of a
// model file, or of an identification). Throws Error naming the first monitored parameter
// missing from either map, and the errors of monitored_parameters for a family diagnostics
// does not monitor; the window is validated (finite values, sigmas >= 0). An empty
// `uncertainty` (a method that reports none, e.g. closed-loop) gives sigma 0 for every
// parameter: the scatter learned by the baseline is then the whole sigma_eff (baseline.hpp).
EstimateWindow estimate_window(const std::string& family, const std::map<std::string, double>& physical,
                               const std::map<std::string, double>& uncertainty, double time,
                               const std::string& plant_id, Source source);

// The window of an identified window of samples (ident::identify_window), of its model's plant.
EstimateWindow estimate_window(const ident::WindowIdentification& identification, double time,
                               const std::string& plant_id, Source source);

}  // namespace ambid::diag
