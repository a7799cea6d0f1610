#pragma once
// The estimate window of one identification: the monitored physical parameters of
// amb1dof_voltage (fault_isolation.hpp: R1 R2 kw1 kw2 kr1 kr2 ks) with the one-sigma
// uncertainty the identifier reports for each.
#include <map>
#include <string>

#include "diagnostics/estimate.hpp"
#include "identifier/families/amb1dof_deadbeat.hpp"

namespace ambid::diag {

// The parameters a window of amb1dof_voltage carries, in this order.
const std::vector<std::string>& monitored_amb1dof_parameters();

// From the physical values and their uncertainties (the `physical` and `uncertainty` of a
// model file, or of an identification). Throws Error naming the first monitored parameter
// missing from either map; the window is validated (finite values, sigmas >= 0). An empty
// `uncertainty` (a method that reports none, e.g. closed-loop) gives sigma 0 for every
// parameter: the scatter learned by the baseline is then the whole sigma_eff (baseline.hpp).
EstimateWindow estimate_window(const std::map<std::string, double>& physical,
                               const std::map<std::string, double>& uncertainty, double time,
                               const std::string& plant_id, Source source);

EstimateWindow estimate_window(const ident::Amb1dofIdentification& identification, double time,
                               const std::string& plant_id, Source source);

}  // namespace ambid::diag
