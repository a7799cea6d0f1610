#pragma once
// Data-driven starting values of the maglev1coil_voltage audit's candidates: the family's
// grey-box fit (the identifier's method greybox, identifier/plant_families.hpp) reads the force-law exponents and the
// coil resistance from x, i, u directly, so force_law and coil_resistance start where the data
// put them, not only at the catalogue's typical sizes (from one of which the two-exponent fit
// fell into a local minimum that keeps the levels' currents but not the dynamics).
#include <vector>

#include "core/experiment.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag {

// Empty when the grey-box fit cannot be computed on this record (said by the audit's other
// starts taking over), or its values lie outside the catalogue's ranges.
std::vector<sim::Effect> maglev_audit_starts(const Experiment& measured);

}  // namespace ambid::diag
