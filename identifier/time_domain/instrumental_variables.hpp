#pragma once
// Instrumental-variable least squares (two-stage least squares), by QR only:
//   theta = argmin || P_W (Phi theta - Z) ||,  P_W the projector onto the instruments' span.
// With W = Q_w R_w, the QR factor of [W | Phi | Z] gives Q_w' Phi and Q_w' Z as its top rows,
// and theta is the ordinary least-squares solution of those (LeastSquaresAccumulator, with
// its rank and condition checks: instruments that do not correlate with the regressors show
// up as a rank-deficient or ill-conditioned projected problem).
// Consistent when the equation error is uncorrelated with the instruments even if it is
// correlated with the regressors (closed-loop data: sensor noise fed back into u), e.g.
// instruments built from the excitation r.
// The residual covariance is that of the original equations (Z - Phi theta, rows - regressors
// degrees of freedom); inverse_gram is (Phi' P_W Phi)^-1, so the covariances are the usual
// asymptotic IV ones.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "identifier/time_domain/least_squares.hpp"

namespace ambid::ident {

// phi: rows x regressors, z: rows x targets, instruments: rows x (>= regressors). Throws Error
// for inconsistent sizes, InsufficientData as LeastSquaresAccumulator::solve (too few rows or
// instruments, rank deficient or ill-conditioned).
LeastSquaresSolution solve_instrumental_variables(const Eigen::MatrixXd& phi, const Eigen::MatrixXd& z,
                                                  const Eigen::MatrixXd& instruments,
                                                  const std::vector<std::string>& regressor_names,
                                                  const LeastSquaresOptions& options = {});

}  // namespace ambid::ident
