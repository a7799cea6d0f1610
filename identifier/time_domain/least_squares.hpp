#pragma once
// Streaming linear least squares  Phi theta ~= Z  by block Householder QR.
//
// Rows arrive in blocks. Only the upper-triangular factor R of the augmented matrix
// [Phi | Z] is kept: each new block is stacked below the current R and [R; block] is
// re-triangularised (Householder QR; Q is never formed). Phi' Phi is never formed: the
// solution, the rank and condition checks and the covariances all come from R.
//
// With R = [R11 R12; 0 R22] (R11 regressors x regressors, R22 targets x targets):
//   theta          = R11^-1 R12
//   E' E           = (R12 - R11 theta)' (R12 - R11 theta) + R22' R22   (E = Z - Phi theta)
//   (Phi' Phi)^-1  = R11^-1 R11^-T
//
// Tikhonov regularisation (minimise ||Phi theta - Z||^2 + lambda ||theta||^2) appends
// sqrt(lambda) I rows below [R11 R12] and triangularises again (S11, S12):
//   theta = S11^-1 S12, parameter covariance sigma^2 (S'S)^-1 R11'R11 (S'S)^-1 (sandwich form).
//
// Rank and condition are judged on the column-equilibrated factor R11 diag(1/||Phi_j||), so
// they do not depend on the units of the regressors. Its singular values come from a Jacobi
// SVD of the (small, square) factor.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ambid::ident {

struct LeastSquaresOptions {
  // Tikhonov weight lambda >= 0 on ||theta||^2 (unscaled theta, i.e. in the regressors' units).
  double regularization = 0.0;
  // A singular value of the column-equilibrated factor counts as zero when it is below
  // rank_tolerance times the largest. <= 0 selects max(rows, regressors) * machine epsilon.
  double rank_tolerance = 0.0;
  // Largest accepted condition number of the column-equilibrated factor (a full-rank problem
  // beyond it is refused as InsufficientData). Its reciprocal bounds the relative accuracy of
  // the weakest parameter combination in units of machine epsilon.
  double max_condition = 1e10;
};

struct LeastSquaresSolution {
  Eigen::MatrixXd theta;                // regressors x targets
  Eigen::Index rows = 0;                // data rows that went into the fit
  Eigen::Index degrees_of_freedom = 0;  // rows - regressors
  Eigen::Index rank = 0;                // numerical rank of the column-equilibrated factor
  double condition_number = 0.0;        // of the column-equilibrated (regularised) factor
  double raw_condition_number = 0.0;    // of the (regularised) factor as is, unit dependent
  Eigen::VectorXd singular_values;      // column-equilibrated factor, descending
  Eigen::VectorXd column_norms;         // ||Phi(:, j)|| of every regressor
  Eigen::MatrixXd residual_gram;        // E' E, targets x targets
  Eigen::MatrixXd residual_covariance;  // E' E / degrees_of_freedom
  // Unscaled parameter covariance: (Phi' Phi)^-1 from R11^-1 (sandwich form when regularised).
  // Cov(theta(i, j), theta(k, l)) = residual_covariance(j, l) * inverse_gram(i, k).
  Eigen::MatrixXd inverse_gram;

  // Covariance of the column `target` of theta (regressors x regressors).
  Eigen::MatrixXd parameter_covariance(Eigen::Index target) const;
  // Cov(theta(i, j), theta(k, l)).
  double covariance(Eigen::Index i, Eigen::Index j, Eigen::Index k, Eigen::Index l) const;
  // One standard deviation of every entry of theta (regressors x targets).
  Eigen::MatrixXd standard_deviations() const;
};

class LeastSquaresAccumulator {
 public:
  // `regressor_names` (optional, one per regressor) are used in error messages.
  LeastSquaresAccumulator(Eigen::Index regressors, Eigen::Index targets, std::vector<std::string> regressor_names = {});

  // Appends rows: phi is rows x regressors, z rows x targets. Throws Error on a dimension
  // mismatch or a non-finite entry (naming the row, counted from the first row ever added).
  void add(const Eigen::Ref<const Eigen::MatrixXd>& phi, const Eigen::Ref<const Eigen::MatrixXd>& z);

  Eigen::Index regressors() const { return regressors_; }
  Eigen::Index targets() const { return targets_; }
  Eigen::Index rows() const { return rows_; }
  const std::vector<std::string>& regressor_names() const { return names_; }

  // The upper-triangular factor of [Phi | Z], (regressors + targets) square (zero rows where
  // fewer data rows than columns have arrived).
  Eigen::MatrixXd factor() const;

  // Solves the problem. Throws InsufficientData when there are not more rows than regressors,
  // when a regressor is identically zero, when the regressors are rank deficient (says how
  // many directions lack excitation and which regressors they involve), or when the condition
  // number exceeds options.max_condition. Throws Error for invalid options.
  LeastSquaresSolution solve(const LeastSquaresOptions& options = {}) const;

 private:
  void compress(const Eigen::MatrixXd& block);
  void flush_buffer();

  Eigen::Index regressors_, targets_;
  std::vector<std::string> names_;
  Eigen::MatrixXd R_;       // (regressors + targets) square, upper triangular
  Eigen::MatrixXd buffer_;  // rows waiting to be compressed into R_
  Eigen::Index buffered_ = 0;
  Eigen::Index rows_ = 0;
};

// One-shot convenience: accumulates Phi and Z and solves.
LeastSquaresSolution solve_least_squares(const Eigen::MatrixXd& phi, const Eigen::MatrixXd& z,
                                         const LeastSquaresOptions& options = {},
                                         std::vector<std::string> regressor_names = {});

}  // namespace ambid::ident
