#include "plant_sim/dare.hpp"

#include <cmath>
#include <complex>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::sim {
namespace {

constexpr int kMaxIterations = 100;
constexpr double kConvergence = 1e-14;

void require_dare(bool ok, const std::string& message) {
  if (!ok) throw Error("DARE: " + message);
}

void require_symmetric(const Eigen::MatrixXd& M, const char* name) {
  const double asym = (M - M.transpose()).norm();
  if (asym > 1e-10 * std::max(1.0, M.norm())) {
    std::ostringstream msg;
    msg << name << " must be symmetric; ||" << name << " - " << name << "'|| = " << asym;
    require_dare(false, msg.str());
  }
}

void check_inputs(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                  const Eigen::MatrixXd& R, const Eigen::MatrixXd& N) {
  const Eigen::Index n = A.rows(), m = B.cols();
  require_dare(A.rows() == A.cols(), "A must be square, got " + dims(A));
  require_dare(n > 0, "A is empty");
  require_dare(B.rows() == n && m > 0, "B must have " + std::to_string(n) + " rows, got " + dims(B));
  require_dare(Q.rows() == n && Q.cols() == n,
               "Q must be " + std::to_string(n) + "x" + std::to_string(n) + ", got " + dims(Q));
  require_dare(R.rows() == m && R.cols() == m,
               "R must be " + std::to_string(m) + "x" + std::to_string(m) + ", got " + dims(R));
  require_dare(N.size() == 0 || (N.rows() == n && N.cols() == m),
               "N must be empty or " + std::to_string(n) + "x" + std::to_string(m) + ", got " + dims(N));
  require_dare(A.allFinite() && B.allFinite() && Q.allFinite() && R.allFinite() && N.allFinite(),
               "a matrix has a non-finite entry");
  require_symmetric(Q, "Q");
  require_symmetric(R, "R");
  const double r_lowest = linalg::symmetric_eigenvalues(R).minCoeff();
  if (!(r_lowest > 1e-14 * std::max(1.0, R.norm()))) {
    std::ostringstream msg;
    msg << "R must be positive definite; smallest eigenvalue " << r_lowest;
    require_dare(false, msg.str());
  }
  Eigen::MatrixXd joint = Eigen::MatrixXd::Zero(n + m, n + m);
  joint.topLeftCorner(n, n) = Q;
  joint.bottomRightCorner(m, m) = R;
  if (N.size() != 0) {
    joint.topRightCorner(n, m) = N;
    joint.bottomLeftCorner(m, n) = N.transpose();
  }
  joint = 0.5 * (joint + joint.transpose());
  const double lowest = linalg::symmetric_eigenvalues(joint).minCoeff();
  if (lowest < -1e-10 * std::max(1.0, joint.norm())) {
    std::ostringstream msg;
    msg << "[Q N; N' R] must be positive semidefinite; smallest eigenvalue " << lowest;
    require_dare(false, msg.str());
  }
}

// PBH test: every eigenvalue of A on or outside the unit circle must be controllable.
void check_stabilisable(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  const Eigen::Index n = A.rows(), m = B.cols();
  const Eigen::VectorXcd eig = linalg::eigenvalues(A);
  Eigen::MatrixXd AB(n, n + m);
  AB << A, B;
  const double scale = std::max(1.0, AB.norm());
  for (Eigen::Index i = 0; i < eig.size(); ++i) {
    const std::complex<double> z = eig(i);
    if (std::abs(z) < 1.0 - 1e-12) continue;
    Eigen::MatrixXcd pbh(n, n + m);
    pbh.leftCols(n) = A.cast<std::complex<double>>();
    pbh.leftCols(n).diagonal().array() -= z;
    pbh.rightCols(m) = B.cast<std::complex<double>>();
    const double smallest = linalg::singular_values(pbh)(n - 1);
    if (smallest <= 1e-11 * scale) {
      std::ostringstream msg;
      msg << "the pair (A, B) is not stabilisable: eigenvalue " << z.real() << (z.imag() < 0 ? " - " : " + ")
          << std::abs(z.imag()) << "i (|z| = " << std::abs(z) << ") is not controllable";
      require_dare(false, msg.str());
    }
  }
}

}  // namespace

Eigen::MatrixXd dare_residual(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                              const Eigen::MatrixXd& R, const Eigen::MatrixXd& X, const Eigen::MatrixXd& N) {
  Eigen::MatrixXd cross = A.transpose() * X * B;
  if (N.size() != 0) cross += N;
  const Eigen::MatrixXd S = R + B.transpose() * X * B;
  return A.transpose() * X * A - X - cross * linalg::ldlt_solve(S, cross.transpose()) + Q;
}

Eigen::MatrixXd solve_dare(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                           const Eigen::MatrixXd& R, const Eigen::MatrixXd& N) {
  check_inputs(A, B, Q, R, N);
  check_stabilisable(A, B);
  const Eigen::Index n = A.rows();

  // Remove the cross term: u = v - R^{-1} N' x gives A - B R^{-1} N' and Q - N R^{-1} N'.
  Eigen::MatrixXd Ak = A, Hk = Q;
  if (N.size() != 0) {
    const Eigen::MatrixXd RinvNt = linalg::llt_solve(R, N.transpose());
    Ak -= B * RinvNt;
    Hk -= N * RinvNt;
  }
  Eigen::MatrixXd Gk = B * linalg::llt_solve(R, B.transpose());
  Gk = 0.5 * (Gk + Gk.transpose());
  Hk = 0.5 * (Hk + Hk.transpose());

  // SDA: A' X (I + G X)^{-1} A + H = X; H_k converges to X.
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  bool converged = false;
  double change = 0.0;
  for (int k = 0; k < kMaxIterations && !converged; ++k) {
    const Eigen::MatrixXd W = I + Gk * Hk;
    const Eigen::MatrixXd WA = linalg::lu_solve(W, Ak).x;
    const Eigen::MatrixXd WG = linalg::lu_solve(W, Gk).x;
    Eigen::MatrixXd H_next = Hk + Ak.transpose() * Hk * WA;
    Eigen::MatrixXd G_next = Gk + Ak * WG * Ak.transpose();
    Ak = Ak * WA;
    H_next = 0.5 * (H_next + H_next.transpose());
    G_next = 0.5 * (G_next + G_next.transpose());
    require_dare(H_next.allFinite() && G_next.allFinite() && Ak.allFinite(),
                 "doubling iteration diverged (non-finite iterate at step " + std::to_string(k + 1) +
                     "); no stabilising solution");
    change = (H_next - Hk).norm();
    converged = change <= kConvergence * std::max(1.0, H_next.norm());
    Hk = std::move(H_next);
    Gk = std::move(G_next);
  }
  if (!converged) {
    std::ostringstream msg;
    msg << "doubling iteration did not converge in " << kMaxIterations << " steps (last relative change "
        << change / std::max(1.0, Hk.norm()) << "); an eigenvalue on the unit circle may be unobserved by Q";
    require_dare(false, msg.str());
  }

  // The solution must be stabilising.
  Eigen::MatrixXd cross = A.transpose() * Hk * B;
  if (N.size() != 0) cross += N;
  const Eigen::MatrixXd K = linalg::ldlt_solve(R + B.transpose() * Hk * B, cross.transpose());
  const double radius = linalg::spectral_radius(A - B * K);
  if (!(radius < 1.0)) {
    std::ostringstream msg;
    msg << "no stabilising solution: closed-loop spectral radius " << radius
        << " (a mode on the unit circle is not seen by Q)";
    require_dare(false, msg.str());
  }
  return Hk;
}

}  // namespace ambid::sim
