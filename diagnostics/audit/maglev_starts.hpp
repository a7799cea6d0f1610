#pragma once
// Data-driven starting values of the maglev1coil_voltage audit's candidates: the family's
// grey-box fit (the identifier's method greybox, identifier/plant_families.hpp) reads the force-law exponents and the
// coil resistance from x, i, u directly, so force_law and coil_resistance (and amplifier_gain at
// the gain that gives the same steady current) start where the data put them, not only at the catalogue's typical sizes
// (from one of which the two-exponent fit fell into a local minimum that keeps the levels' currents but not the
// dynamics). Besides: sensor_delay at one and two samples (the catalogue's 3 ms and 0.9 ms lie between the samples of
// a 1.3 ms rig, where the fit of a whole-sample delay starts on the wrong side of a kink), actuator_quantisation at the
// step the current reads (audit_quantisation.hpp); sensor_offset and sensor_gain where the grey-box exponents put
// them (maglev_starts.cpp: an offset or a scale of the sensor reads as the force law's exponents).
#include <vector>

#include "core/experiment.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag {

// Without the grey-box starts when its fit cannot be computed on this record (the audit's
// other starts take over); a start outside the catalogue's ranges is left out.
std::vector<sim::Effect> maglev_audit_starts(const Experiment& measured);

}  // namespace ambid::diag
