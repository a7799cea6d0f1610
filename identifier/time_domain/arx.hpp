#pragma once
// Multi-input multi-output ARX models by least squares (the streaming QR accumulator):
//
//   z[k] = sum_{i=1..q} a_i y[k-i] + sum_{i=1..q} b_i u[k-i]  (+ b_0 u[k])  + e[k]
//
// Usually the target z is y itself (the ARX model of y); the second overload regresses another
// signal z (e.g. the feedback signal u_f of Lee ch. 4, eq. 4.21) on the same past of y and u.
// Equations are formed for k = q .. N-1 only (no zero padding of unknown initial samples).
//
// Regressor order (Lee 4.22): [u[k] (when direct_term), y[k-1], u[k-1], ..., y[k-q], u[k-q]],
// channel by channel, named "u2[k]", "y1[k-3]", ... in error messages.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "identifier/time_domain/least_squares.hpp"

namespace ambid::ident {

struct ArxOptions {
  Eigen::Index order = 0;    // q >= 1
  bool direct_term = false;  // estimate b_0 (puts u[k] among the regressors)
  LeastSquaresOptions least_squares;
  // Signal names used in error messages ("r" makes them read "r2[k-1]").
  std::string output_symbol = "y";
  std::string input_symbol = "u";
  // Samples where a new piece of record starts (records joined end to end, e.g. a jackknife
  // sub-record): equations whose window k-q .. k crosses one are left out.
  std::vector<Eigen::Index> breaks;
};

struct ArxModel {
  Eigen::Index order = 0;
  bool direct_term = false;
  Eigen::Index outputs = 0;        // channels of y (columns of a_i)
  Eigen::Index inputs = 0;         // channels of u (columns of b_i)
  Eigen::Index targets = 0;        // channels of z (rows of a_i, b_i)
  std::vector<Eigen::MatrixXd> a;  // a[i-1] = a_i, targets x outputs, i = 1..q
  std::vector<Eigen::MatrixXd> b;  // b[i] = b_i, targets x inputs, i = 0..q (b[0] = 0 unless direct_term)
  LeastSquaresSolution fit;        // theta = [b_0; a_1; b_1; ...]' in the regressor order above

  // Column of theta (row of the regressor vector) that multiplies channel c of y[k-i] / u[k-i].
  Eigen::Index a_regressor(Eigen::Index i, Eigen::Index channel) const;
  Eigen::Index b_regressor(Eigen::Index i, Eigen::Index channel) const;
  // One standard deviation of every entry of a_i (i >= 1) / b_i (i >= 0; zeros for b_0
  // without direct_term).
  Eigen::MatrixXd a_standard_deviation(Eigen::Index i) const;
  Eigen::MatrixXd b_standard_deviation(Eigen::Index i) const;
  // Covariance of the entries (target r1, regressor j1) and (target r2, regressor j2).
  double covariance(Eigen::Index r1, Eigen::Index j1, Eigen::Index r2, Eigen::Index j2) const;
};

// ARX model of y on its own past and the past (and optionally present) of u.
// y: samples x outputs, u: samples x inputs (inputs may be 0 for a pure AR model).
// Throws Error on inconsistent shapes, a non-finite sample or order < 1, and InsufficientData
// when the record is too short for the number of regressors or the data do not excite them
// (as LeastSquaresAccumulator::solve).
ArxModel fit_arx(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u, const ArxOptions& options);

// ARX model of a target z on the past of y and u (a_i multiply y, b_i multiply u).
ArxModel fit_arx(const Eigen::MatrixXd& z, const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                 const ArxOptions& options);

// Residuals z[k] - prediction for k = q .. N-1 ((N - q) x targets).
Eigen::MatrixXd arx_residuals(const ArxModel& model, const Eigen::MatrixXd& z, const Eigen::MatrixXd& y,
                              const Eigen::MatrixXd& u);

}  // namespace ambid::ident
