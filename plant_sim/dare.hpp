#pragma once
// Discrete algebraic Riccati equation (DARE) by the structure-preserving doubling algorithm
// (SDA; Chu, Fan, Lin, Wang 2004). The doubling converges quadratically to the stabilising
// solution whenever it exists, and needs neither an invertible A nor an ordered Schur form.
#include <Eigen/Core>

namespace ambid::sim {

// The stabilising solution X = X' >= 0 of
//   A'XA - X - (A'XB + N)(R + B'XB)^{-1}(B'XA + N') + Q = 0,
// i.e. the one for which A - B K, K = (R + B'XB)^{-1}(B'XA + N'), has every eigenvalue inside
// the unit circle. N (n x m) may be empty (no cross term).
// Throws Error naming the offending value when dimensions disagree, an entry is not finite,
// Q or R is not symmetric, R is not positive definite, [Q N; N' R] is not positive
// semidefinite, (A, B) is not stabilisable (names the uncontrollable eigenvalue on or outside
// the unit circle), or the doubling does not converge (e.g. an eigenvalue on the unit circle
// that the weight Q does not see).
Eigen::MatrixXd solve_dare(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                           const Eigen::MatrixXd& R, const Eigen::MatrixXd& N = Eigen::MatrixXd());

// The left-hand side of the equation above for a given X (zero at the solution).
Eigen::MatrixXd dare_residual(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                              const Eigen::MatrixXd& R, const Eigen::MatrixXd& X,
                              const Eigen::MatrixXd& N = Eigen::MatrixXd());

}  // namespace ambid::sim
