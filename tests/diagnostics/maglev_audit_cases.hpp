#pragma once
// Effects of the maglev catalogue hidden in rig records (tests/support/maglev_records.hpp):
// each case changes the truth or the rig's board the way the real thing would, while the
// sidecar stays nominal.
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "plant_sim/maglev_parameters.hpp"
#include "plant_sim/maglev_rig.hpp"

namespace ambid::diag::testing {

struct MaglevCase {
  std::string effect;  // the catalogue's name; "none" for a clean record
  sim::MaglevParameters truth;
  sim::MaglevRig rig;
};

// The truth with force constant set so that the body hangs at 14 mm with 19 mA (as the rig's).
sim::MaglevParameters maglev_truth(double n_i, double n_x);

// "none", "sensor_nonlinearity", "force_law", "actuator_quantisation", "sensor_delay",
// "coil_resistance", "sensor_offset", "sensor_gain" (the last three for the slow sweep).
MaglevCase maglev_case(const std::string& effect);

// The record of `c` at `sample_time` with `samples` samples (seeded).
Experiment maglev_case_record(const MaglevCase& c, double sample_time, Eigen::Index samples, std::uint64_t seed);

}  // namespace ambid::diag::testing
