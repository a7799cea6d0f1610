#pragma once
// The resolution a record was logged at, read from the record itself: a rig that prints
// 0.01 mm, 0.01 V, 0.01 mA leaves every logged value a whole multiple of that step, which a
// full-precision record never is. The audit's replay follows the rounded record with it
// (plant_sim/closed_loop.hpp, ClosedLoopOptions::followed): driven by the excitation
// reconstructed from the rounded record (r = u - C y_logged), it then does not answer a
// rounding the plant never had (at 1.3 ms the rig's derivative gain turns 0.01 mm into 0.77 V).
#include <Eigen/Core>

namespace ambid::diag {

// Per column: the largest step q = 1, 2 or 5 times a power of ten (1e-12 to 1e3, in the
// column's units) of which every value is a whole multiple (to 1e-6 q), 0 when there is none
// or the column holds fewer than two distinct values.
Eigen::VectorXd logging_resolution(const Eigen::MatrixXd& logged);

}  // namespace ambid::diag
