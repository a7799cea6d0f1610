#include "identifier/frequency_domain/frf_linalg.hpp"

#include "core/linalg.hpp"

namespace ambid::ident {

Eigen::MatrixXcd left_solve(const Eigen::MatrixXcd& A, const Eigen::MatrixXcd& B) { return linalg::svd_solve(A, B); }

Eigen::MatrixXcd right_solve(const Eigen::MatrixXcd& B, const Eigen::MatrixXcd& A) {
  return left_solve(A.transpose(), B.transpose()).transpose();
}

double inverse_condition(const Eigen::MatrixXcd& A) {
  if (A.size() == 0) return 0.0;
  const Eigen::VectorXd s = linalg::singular_values(A);
  if (!(s(0) > 0.0)) return 0.0;
  return s(s.size() - 1) / s(0);
}

double max_singular_value(const Eigen::MatrixXcd& A) {
  if (A.size() == 0) return 0.0;
  return linalg::singular_values(A)(0);
}

}  // namespace ambid::ident
