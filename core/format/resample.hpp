#pragma once
// Non-uniform samples onto a uniform grid, shared by the experiment reader's resampling and
// `ambid import --resample`.
#include <Eigen/Core>

namespace ambid {

// Linear interpolation of `values` (one row per entry of `t`, t strictly increasing, at least
// 2 rows) onto the grid t(0) + k T, k = 0, 1, ... up to t's last entry (kept when the span is a
// whole number of steps, within 1e-9 of a step). Replaces t and values.
void resample_linear(Eigen::VectorXd& t, Eigen::MatrixXd& values, double T);

// The number of grid points resample_linear would produce.
Eigen::Index resampled_length(const Eigen::VectorXd& t, double T);

}  // namespace ambid
