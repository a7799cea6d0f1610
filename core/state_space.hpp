#pragma once
// Linear time-invariant state-space systems, continuous and discrete, and the exact
// zero-order-hold map between them (seed 000 eq. 7-8).
#include <Eigen/Core>

namespace ambid {

// x' = A x + B u,  y = C x + D u
struct ContinuousSystem {
  Eigen::MatrixXd A, B, C, D;

  Eigen::Index states() const { return A.rows(); }
  Eigen::Index inputs() const { return B.cols(); }
  Eigen::Index outputs() const { return C.rows(); }
  // Throws Error naming the first inconsistent dimension or non-finite entry.
  void validate() const;
};

// x[k+1] = A x[k] + B u[k],  y[k] = C x[k] + D u[k],  sampled every `sample_time` seconds.
struct DiscreteSystem {
  Eigen::MatrixXd A, B, C, D;
  double sample_time = 0.0;

  Eigen::Index states() const { return A.rows(); }
  Eigen::Index inputs() const { return B.cols(); }
  Eigen::Index outputs() const { return C.rows(); }
  void validate() const;
};

// Exact ZOH discretisation: [Ad Bd; 0 I] = expm([A B; 0 0] T).
DiscreteSystem c2d_zoh(const ContinuousSystem& sys, double sample_time);

// Inverse of c2d_zoh by the principal matrix logarithm (seed 000 eq. 8):
// [A B; 0 0] = logm([Ad Bd; 0 I]) / T. Refuses, naming the eigenvalue, when Ad has an
// eigenvalue on the closed negative real axis (no real logarithm exists) or at zero: throws
// NoContinuousEquivalent (no_continuous_equivalent.hpp) then.
ContinuousSystem d2c_zoh(const DiscreteSystem& sys);

// Simulates the discrete system from state x0. `u` has one row per sample, one column per
// input; the result has one row per sample, one column per output.
Eigen::MatrixXd simulate(const DiscreteSystem& sys, const Eigen::MatrixXd& u, const Eigen::VectorXd& x0);
Eigen::MatrixXd simulate(const DiscreteSystem& sys, const Eigen::MatrixXd& u);

// Continuous and discrete poles.
Eigen::VectorXcd poles(const ContinuousSystem& sys);
Eigen::VectorXcd poles(const DiscreteSystem& sys);

}  // namespace ambid
