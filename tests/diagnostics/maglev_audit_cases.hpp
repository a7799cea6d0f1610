#pragma once
// Effects of the maglev catalogue hidden in rig records (tests/support/maglev_records.hpp):
// each case changes the truth or the rig's board the way the real thing would, while the
// sidecar stays nominal.
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "plant_sim/maglev_loop.hpp"
#include "plant_sim/maglev_parameters.hpp"
#include "plant_sim/maglev_rig.hpp"

namespace ambid::diag::testing {

struct MaglevCase {
  std::string effect;  // the catalogue's name; "none" for a clean record
  sim::MaglevParameters truth;
  sim::MaglevRig rig;
  double harmonic_force = 0.0, harmonic_frequency = 0.0;  // N, Hz: sim::MaglevRunOptions
};

// The truth with force constant set so that the body hangs at 14 mm with 19 mA (as the rig's).
sim::MaglevParameters maglev_truth(double n_i, double n_x);

// "none" or an effect of the catalogue (maglev_case_effects()).
MaglevCase maglev_case(const std::string& effect);

// Every effect of the maglev catalogue, in its order (plant_sim/maglev_effects.hpp).
std::vector<std::string> maglev_case_effects();

// The record of `c` with the run's options (test_support::maglev_run_options) and the case's
// harmonic force.
Experiment maglev_case_record(const MaglevCase& c, sim::MaglevRunOptions run);

}  // namespace ambid::diag::testing
