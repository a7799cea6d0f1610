#pragma once
// Dense decompositions behind plain functions on dynamic matrices, compiled once in
// core/linalg.cpp: a translation unit that instantiates an Eigen decomposition pays 10-20 s of
// compile and ~20 MB of object, so no other file includes Eigen's decomposition modules.
// Each function keeps the algorithm and thresholds its callers used before (JacobiSVD,
// column-pivoting Householder QR, ...). Non-square input where a square one is needed, and
// right-hand sides of the wrong height, throw ambid::Error naming the dimensions.
#include <optional>

#include <Eigen/Core>

namespace ambid::linalg {

// A least-squares solution with the numerical rank of the factorised matrix.
template <class Solution>
struct RankedSolution {
  Solution x;
  Eigen::Index rank = 0;
};

// A linear-system solution with the LU estimate of the reciprocal 1-norm condition number.
template <class Solution>
struct ConditionedSolution {
  Solution x;
  double rcond = 0.0;
};

// Thin singular value decomposition A = U diag(S) V^T, S descending.
struct Svd {
  Eigen::MatrixXd U;
  Eigen::VectorXd S;
  Eigen::MatrixXd V;
};

// Eigen decomposition A = V diag(values) V^H of a Hermitian matrix, values ascending.
struct HermitianEigen {
  Eigen::VectorXd values;
  Eigen::MatrixXcd vectors;  // orthonormal columns, one per value
};

// A Moore-Penrose pseudo-inverse with the numerical rank it was formed with.
struct PseudoInverse {
  Eigen::MatrixXd pinv;
  Eigen::Index rank = 0;
};

// Relative threshold meaning "the decomposition's default" (min(rows, cols) * machine epsilon).
inline constexpr double kDefaultThreshold = -1.0;

// --- eigenvalues (Hessenberg/real Schur; eigenvalues only)
// Eigenvalues of a real square matrix, in the solver's order.
Eigen::VectorXcd eigenvalues(const Eigen::MatrixXd& A);
// Largest eigenvalue magnitude of a square matrix; 0 for an empty one.
double spectral_radius(const Eigen::MatrixXd& A);
// Eigenvalues of a symmetric matrix (lower triangle read), ascending.
Eigen::VectorXd symmetric_eigenvalues(const Eigen::MatrixXd& A);
// Eigenvalues and eigenvectors of a Hermitian matrix (lower triangle read).
HermitianEigen hermitian_eigen(const Eigen::MatrixXcd& A);

// --- singular values (one-sided Jacobi SVD)
// Singular values, descending.
Eigen::VectorXd singular_values(const Eigen::MatrixXd& A);
Eigen::VectorXd singular_values(const Eigen::MatrixXcd& A);
// Thin SVD with U and V.
Svd svd(const Eigen::MatrixXd& A);
// sigma_max / sigma_min (infinite when A is rank deficient); A must not be empty.
double condition_number(const Eigen::MatrixXd& A);
// Minimum-norm least-squares X of A X = B; singular values <= rcond * sigma_max count as zero.
Eigen::MatrixXd svd_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double rcond = kDefaultThreshold);
Eigen::MatrixXcd svd_solve(const Eigen::MatrixXcd& A, const Eigen::MatrixXcd& B, double rcond = kDefaultThreshold);

// --- rank-revealing QR (Householder QR with column pivoting)
// Least-squares X of A X = B and the numerical rank of A: pivots |r_kk| <= threshold * |r_00|
// count as zero (their unknowns are set to zero).
RankedSolution<Eigen::MatrixXd> qr_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                         double threshold = kDefaultThreshold);
RankedSolution<Eigen::VectorXd> qr_solve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                         double threshold = kDefaultThreshold);
RankedSolution<Eigen::MatrixXcd> qr_solve(const Eigen::MatrixXcd& A, const Eigen::MatrixXcd& B,
                                          double threshold = kDefaultThreshold);
// R of A = Q R by Householder QR without pivoting: the min(rows, cols) x cols upper trapezoid.
Eigen::MatrixXd qr_r(const Eigen::MatrixXd& A);
// Q of a square A = Q R by Householder QR without pivoting (an orthogonal matrix).
Eigen::MatrixXd qr_q(const Eigen::MatrixXd& A);
// (J^T J)^-1 = P R^-1 R^-T P^T from J P = Q R without forming J^T J; empty when rank(J) < cols.
Eigen::MatrixXd qr_inverse_gram(const Eigen::MatrixXd& J, double threshold = kDefaultThreshold);
// Orthonormal basis (columns) of the null space of A: the full-pivoting LU kernel,
// orthonormalised by Householder QR; n x 0 when A has full column rank.
Eigen::MatrixXd null_space(const Eigen::MatrixXd& A);
// Orthonormal basis (columns) of the column space of A, one column per unit of its numerical
// rank (column-pivoting Householder QR; threshold as in qr_solve).
Eigen::MatrixXd column_space(const Eigen::MatrixXd& A, double threshold = kDefaultThreshold);
// Pseudo-inverse by the complete orthogonal decomposition.
PseudoInverse pseudo_inverse(const Eigen::MatrixXd& A);

// --- square systems
// Numerical rank by full-pivoting LU.
Eigen::Index rank(const Eigen::MatrixXd& A);
// A^-1 B by full-pivoting LU; nullopt when A is numerically singular.
std::optional<Eigen::MatrixXd> regular_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);
// A^-1 by full-pivoting LU; nullopt when A is numerically singular.
std::optional<Eigen::MatrixXd> regular_inverse(const Eigen::MatrixXd& A);
// A^-1 B by partial-pivoting LU (no singularity check; see rcond).
ConditionedSolution<Eigen::MatrixXd> lu_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);
ConditionedSolution<Eigen::MatrixXcd> lu_solve(const Eigen::MatrixXcd& A, const Eigen::MatrixXcd& B);
// A^-1 by partial-pivoting LU, as Eigen's inverse() of a dynamic matrix (no singularity check).
Eigen::MatrixXd inverse(const Eigen::MatrixXd& A);
// A^-1 of a 3x3 matrix in closed form (cofactors; no allocation, for inner loops; no
// singularity check).
Eigen::Matrix3d inverse_3x3(const Eigen::Matrix3d& A);
// A^-1 B for symmetric positive definite A by Cholesky (LL^T); lower triangle read.
Eigen::MatrixXd llt_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);
// A^-1 B for symmetric positive (semi)definite A by pivoting LDL^T; lower triangle read.
Eigen::MatrixXd ldlt_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);

// --- matrix functions
// Matrix exponential (scaling and squaring with Pade approximants).
Eigen::MatrixXd matrix_exp(const Eigen::MatrixXd& A);
// Principal matrix logarithm (inverse scaling and squaring); non-finite when none exists.
Eigen::MatrixXd matrix_log(const Eigen::MatrixXd& A);

}  // namespace ambid::linalg
