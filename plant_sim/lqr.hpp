#pragma once
// Discrete linear-quadratic regulator and, by duality, the steady-state prediction observer
// (Kalman predictor) gain. Both solve one DARE (dare.hpp).
#include <Eigen/Core>

namespace ambid::sim {

struct LqrGain {
  Eigen::MatrixXd K;                   // u[k] = -K x[k]
  Eigen::MatrixXd X;                   // stabilising DARE solution
  Eigen::VectorXcd closed_loop_poles;  // eigenvalues of A - B K
};

// Minimises sum_k x'Qx + u'Ru + 2 x'Nu for x[k+1] = A x[k] + B u[k]. N may be empty.
// Errors as solve_dare (unstabilisable pair, non-convergence, bad weights).
LqrGain dlqr(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R,
             const Eigen::MatrixXd& N = Eigen::MatrixXd());

struct ObserverGain {
  Eigen::MatrixXd L;                // xh[k+1] = A xh[k] + B u[k] + L (y[k] - C xh[k])
  Eigen::MatrixXd P;                // stabilising solution of the dual DARE
  Eigen::VectorXcd observer_poles;  // eigenvalues of A - L C
};

// Steady-state Kalman predictor gain for x[k+1] = A x + B u + w, y = C x + v with process
// covariance W (n x n) and measurement covariance V (q x q): the dual DARE
// (A', C', W, V). Throws Error when (C, A) is not detectable (names the eigenvalue) or as
// solve_dare.
ObserverGain predictor_gain(const Eigen::MatrixXd& A, const Eigen::MatrixXd& C, const Eigen::MatrixXd& W,
                            const Eigen::MatrixXd& V);

}  // namespace ambid::sim
