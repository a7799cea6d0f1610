// The one translation unit that instantiates Eigen's decompositions (see linalg.hpp).
#include "core/linalg.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <unsupported/Eigen/MatrixFunctions>

#include "core/error.hpp"

namespace ambid::linalg {
namespace {

template <class M>
void require_square(const M& A, const char* who) {
  if (A.rows() != A.cols()) throw Error(std::string("linalg::") + who + ": matrix must be square, got " + dims(A));
}

template <class MA, class MB>
void require_same_rows(const MA& A, const MB& B, const char* who) {
  if (A.rows() != B.rows())
    throw Error(std::string("linalg::") + who + ": right-hand side must have " + std::to_string(A.rows()) +
                " rows like the " + dims(A) + " matrix, got " + dims(B));
}

template <class M>
Eigen::MatrixX<typename M::Scalar> jacobi_svd_solve(const M& A, const M& B, double rcond) {
  require_same_rows(A, B, "svd_solve");
  Eigen::JacobiSVD<M> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  if (rcond >= 0.0) svd.setThreshold(rcond);
  return svd.solve(B);
}

template <class M, class Rhs>
RankedSolution<Rhs> col_piv_qr_solve(const M& A, const Rhs& B, double threshold) {
  require_same_rows(A, B, "qr_solve");
  Eigen::ColPivHouseholderQR<M> qr(A);
  // The threshold decides rank() only; solve() drops the pivots the factorisation found negligible.
  if (threshold >= 0.0) qr.setThreshold(threshold);
  return {qr.solve(B), qr.rank()};
}

template <class M>
ConditionedSolution<M> partial_piv_lu_solve(const M& A, const M& B) {
  require_square(A, "lu_solve");
  require_same_rows(A, B, "lu_solve");
  const Eigen::PartialPivLU<M> lu(A);
  return {lu.solve(B), lu.rcond()};
}

}  // namespace

Eigen::VectorXcd eigenvalues(const Eigen::MatrixXd& A) {
  require_square(A, "eigenvalues");
  if (A.size() == 0) return Eigen::VectorXcd(0);
  return Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues();
}

double spectral_radius(const Eigen::MatrixXd& A) {
  require_square(A, "spectral_radius");
  if (A.size() == 0) return 0.0;
  return eigenvalues(A).cwiseAbs().maxCoeff();
}

Eigen::VectorXd symmetric_eigenvalues(const Eigen::MatrixXd& A) {
  require_square(A, "symmetric_eigenvalues");
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly).eigenvalues();
}

HermitianEigen hermitian_eigen(const Eigen::MatrixXcd& A) {
  require_square(A, "hermitian_eigen");
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> eig(A);
  return {eig.eigenvalues(), eig.eigenvectors()};
}

Eigen::VectorXd singular_values(const Eigen::MatrixXd& A) {
  return Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues();
}

Eigen::VectorXd singular_values(const Eigen::MatrixXcd& A) {
  return Eigen::JacobiSVD<Eigen::MatrixXcd>(A).singularValues();
}

Svd svd(const Eigen::MatrixXd& A) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  return {svd.matrixU(), svd.singularValues(), svd.matrixV()};
}

double condition_number(const Eigen::MatrixXd& A) {
  if (A.size() == 0) throw Error("linalg::condition_number: matrix is empty (" + dims(A) + ")");
  const Eigen::VectorXd s = singular_values(A);
  if (s(s.size() - 1) == 0.0) return std::numeric_limits<double>::infinity();
  return s(0) / s(s.size() - 1);
}

Eigen::MatrixXd svd_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double rcond) {
  return jacobi_svd_solve(A, B, rcond);
}

Eigen::MatrixXcd svd_solve(const Eigen::MatrixXcd& A, const Eigen::MatrixXcd& B, double rcond) {
  return jacobi_svd_solve(A, B, rcond);
}

RankedSolution<Eigen::MatrixXd> qr_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double threshold) {
  return col_piv_qr_solve(A, B, threshold);
}

RankedSolution<Eigen::VectorXd> qr_solve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, double threshold) {
  return col_piv_qr_solve(A, b, threshold);
}

RankedSolution<Eigen::MatrixXcd> qr_solve(const Eigen::MatrixXcd& A, const Eigen::MatrixXcd& B, double threshold) {
  return col_piv_qr_solve(A, B, threshold);
}

Eigen::MatrixXd qr_r(const Eigen::MatrixXd& A) {
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  return qr.matrixQR().topRows(std::min(A.rows(), A.cols())).triangularView<Eigen::Upper>();
}

Eigen::MatrixXd qr_q(const Eigen::MatrixXd& A) {
  require_square(A, "qr_q");
  return Eigen::HouseholderQR<Eigen::MatrixXd>(A).householderQ();
}

Eigen::MatrixXd qr_inverse_gram(const Eigen::MatrixXd& J, double threshold) {
  const Eigen::Index p = J.cols();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(J);
  if (threshold >= 0.0) qr.setThreshold(threshold);
  if (qr.rank() < p) return {};
  const Eigen::MatrixXd R = qr.matrixR().topLeftCorner(p, p).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd Rinv = R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
  return qr.colsPermutation() * (Rinv * Rinv.transpose()) * qr.colsPermutation().transpose();
}

Eigen::MatrixXd null_space(const Eigen::MatrixXd& A) {
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  const Eigen::Index n = A.cols(), dimension = n - lu.rank();
  if (dimension == 0) return Eigen::MatrixXd(n, 0);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(lu.kernel());
  return qr.householderQ() * Eigen::MatrixXd::Identity(n, dimension);
}

Eigen::MatrixXd column_space(const Eigen::MatrixXd& A, double threshold) {
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (threshold >= 0.0) qr.setThreshold(threshold);
  return qr.householderQ() * Eigen::MatrixXd::Identity(A.rows(), qr.rank());
}

PseudoInverse pseudo_inverse(const Eigen::MatrixXd& A) {
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
  return {cod.pseudoInverse(), cod.rank()};
}

Eigen::Index rank(const Eigen::MatrixXd& A) { return Eigen::FullPivLU<Eigen::MatrixXd>(A).rank(); }

std::optional<Eigen::MatrixXd> regular_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  require_square(A, "regular_solve");
  require_same_rows(A, B, "regular_solve");
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (!lu.isInvertible()) return std::nullopt;
  return Eigen::MatrixXd(lu.solve(B));
}

std::optional<Eigen::MatrixXd> regular_inverse(const Eigen::MatrixXd& A) {
  return regular_solve(A, Eigen::MatrixXd::Identity(A.rows(), A.cols()));
}

ConditionedSolution<Eigen::MatrixXd> lu_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return partial_piv_lu_solve(A, B);
}

ConditionedSolution<Eigen::MatrixXcd> lu_solve(const Eigen::MatrixXcd& A, const Eigen::MatrixXcd& B) {
  return partial_piv_lu_solve(A, B);
}

Eigen::MatrixXd inverse(const Eigen::MatrixXd& A) {
  require_square(A, "inverse");
  return Eigen::PartialPivLU<Eigen::MatrixXd>(A).inverse();
}

Eigen::Matrix3d inverse_3x3(const Eigen::Matrix3d& A) { return A.inverse(); }

Eigen::MatrixXd llt_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  require_square(A, "llt_solve");
  require_same_rows(A, B, "llt_solve");
  const Eigen::LLT<Eigen::MatrixXd> llt(A);
  if (llt.info() != Eigen::Success) throw Error("linalg::llt_solve: matrix is not positive definite");
  return llt.solve(B);
}

Eigen::MatrixXd ldlt_solve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  require_square(A, "ldlt_solve");
  require_same_rows(A, B, "ldlt_solve");
  return A.ldlt().solve(B);
}

Eigen::MatrixXd matrix_exp(const Eigen::MatrixXd& A) {
  require_square(A, "matrix_exp");
  return A.exp();
}

Eigen::MatrixXd matrix_log(const Eigen::MatrixXd& A) {
  require_square(A, "matrix_log");
  return A.log();
}

}  // namespace ambid::linalg
