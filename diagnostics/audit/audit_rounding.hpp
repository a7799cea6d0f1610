#pragma once
// The resolution a record was logged at, as its sidecar states it: a rig record (plant_sim/
// maglev_loop.hpp) keeps its logger's settings under extra.rig.settings, log_NAME for output
// NAME (the rig prints 0.01 mm, 0.01 mA). The audit's replay follows the rounded record with it
// (plant_sim/closed_loop.hpp, ClosedLoopOptions::followed): driven by the excitation
// reconstructed from the rounded record (r = u - C y_logged), it then does not answer a
// rounding the plant never had (at 1.3 ms the rig's derivative gain turns 0.01 mm into 0.77 V).
#include <Eigen/Core>

#include "core/experiment.hpp"

namespace ambid::diag {

// Per output of `e` (y_names order): extra.rig.settings.log_NAME where it is a number > 0,
// else 0 (full precision).
Eigen::VectorXd logging_resolution(const Experiment& e);
// The same for the inputs (u_names order): the rig prints its command at 0.01 V.
Eigen::VectorXd input_logging_resolution(const Experiment& e);

}  // namespace ambid::diag
