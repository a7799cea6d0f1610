#pragma once
// Records of the single-coil maglev rig that the audit's replay did not generate, in the form
// a rig's logs take once imported: the rig loop of plant_sim/maglev_loop.hpp (its own PID with
// every clamp acting on y - reference, the Hall sensor and DAC of MaglevRig, RK4 with 20
// sub-steps, uniform noise w on u that is not logged, 0.01 mm / 0.01 V / 0.01 mA logging), then
// the board's PID in the contract's form (plant_sim/maglev_controller.hpp) and r reconstructed
// as u - controller output, as `ambid import --reconstruct-r` does: w plus the reference's part
// of the command.
#include <cstdint>

#include "core/experiment.hpp"
#include "plant_sim/maglev_loop.hpp"
#include "plant_sim/maglev_parameters.hpp"
#include "plant_sim/maglev_rig.hpp"

namespace ambid::test_support {

// Rig-like defaults: 3.25 ms, 3000 samples, levels 14, 13, 15, 14.5, 16, 13.5 mm held 1.5 s,
// w uniform +-0.5 V, sensor noise 5 um (std) on y, 10 uA on the logged current.
sim::MaglevRunOptions maglev_run_options(double sample_time, Eigen::Index samples, std::uint64_t seed);

// Error (the loop's message) when the body touched a stop.
Experiment maglev_record(const sim::MaglevParameters& truth, const sim::MaglevRig& rig,
                         const sim::MaglevRunOptions& run);

}  // namespace ambid::test_support
