#pragma once
// Small dense helpers of the frequency-domain identifier (SVD-based least squares; never
// normal equations).
#include <Eigen/Core>

namespace ambid::ident {

// X minimising ||X A - B|| (X = B A^+), by the SVD of A^T.
Eigen::MatrixXcd right_solve(const Eigen::MatrixXcd& B, const Eigen::MatrixXcd& A);

// X minimising ||A X - B|| (X = A^+ B), by the SVD of A.
Eigen::MatrixXcd left_solve(const Eigen::MatrixXcd& A, const Eigen::MatrixXcd& B);

// sigma_min / sigma_max of A (0 for an empty or zero matrix); over min(rows, cols) values.
double inverse_condition(const Eigen::MatrixXcd& A);

// Largest singular value.
double max_singular_value(const Eigen::MatrixXcd& A);

}  // namespace ambid::ident
