#include "core/state_space.hpp"

#include <cmath>
#include <complex>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "core/no_continuous_equivalent.hpp"

namespace ambid {
namespace {

void require_finite(const Eigen::MatrixXd& m, const char* name) {
  if (!m.allFinite()) throw Error(std::string("state-space matrix ") + name + " has a non-finite entry");
}

void validate_abcd(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                   const Eigen::MatrixXd& D) {
  if (A.rows() != A.cols()) throw Error("state-space A must be square, got " + dims(A));
  if (B.rows() != A.rows())
    throw Error("state-space B must have " + std::to_string(A.rows()) + " rows (states), got " + dims(B));
  if (C.cols() != A.rows())
    throw Error("state-space C must have " + std::to_string(A.rows()) + " columns (states), got " + dims(C));
  if (D.rows() != C.rows() || D.cols() != B.cols())
    throw Error("state-space D must be " + std::to_string(C.rows()) + "x" + std::to_string(B.cols()) +
                " (outputs x inputs), got " + dims(D));
  require_finite(A, "A");
  require_finite(B, "B");
  require_finite(C, "C");
  require_finite(D, "D");
}

void require_sample_time(double sample_time) {
  if (!(sample_time > 0.0) || !std::isfinite(sample_time))
    throw Error("sample time must be positive and finite, got " + std::to_string(sample_time));
}

}  // namespace

void ContinuousSystem::validate() const { validate_abcd(A, B, C, D); }

void DiscreteSystem::validate() const {
  validate_abcd(A, B, C, D);
  require_sample_time(sample_time);
}

DiscreteSystem c2d_zoh(const ContinuousSystem& sys, double sample_time) {
  sys.validate();
  require_sample_time(sample_time);
  const Eigen::Index n = sys.states(), m = sys.inputs();
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + m, n + m);
  M.topLeftCorner(n, n) = sys.A * sample_time;
  M.topRightCorner(n, m) = sys.B * sample_time;
  const Eigen::MatrixXd E = linalg::matrix_exp(M);
  return DiscreteSystem{E.topLeftCorner(n, n), E.topRightCorner(n, m), sys.C, sys.D, sample_time};
}

ContinuousSystem d2c_zoh(const DiscreteSystem& sys) {
  sys.validate();
  const Eigen::Index n = sys.states(), m = sys.inputs();
  const Eigen::VectorXcd eig = linalg::eigenvalues(sys.A);
  const double scale = std::max(1.0, sys.A.norm());
  for (Eigen::Index i = 0; i < eig.size(); ++i) {
    const std::complex<double> z = eig(i);
    const bool on_negative_axis = std::abs(z.imag()) <= 1e-12 * scale && z.real() <= 0.0;
    if (on_negative_axis) {
      std::ostringstream msg;
      msg << "d2c: discrete eigenvalue " << z.real()
          << " lies on the closed negative real axis; no real matrix logarithm exists (the "
             "discrete model has no continuous zero-order-hold equivalent)";
      throw NoContinuousEquivalent(msg.str());
    }
  }
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(n + m, n + m);
  M.topLeftCorner(n, n) = sys.A;
  M.topRightCorner(n, m) = sys.B;
  const Eigen::MatrixXd L = linalg::matrix_log(M) / sys.sample_time;
  if (!L.allFinite()) throw Error("d2c: matrix logarithm did not converge");
  return ContinuousSystem{L.topLeftCorner(n, n), L.topRightCorner(n, m), sys.C, sys.D};
}

Eigen::MatrixXd simulate(const DiscreteSystem& sys, const Eigen::MatrixXd& u, const Eigen::VectorXd& x0) {
  sys.validate();
  if (u.cols() != sys.inputs())
    throw Error("simulate: input has " + std::to_string(u.cols()) + " columns, system has " +
                std::to_string(sys.inputs()) + " inputs");
  if (x0.size() != sys.states())
    throw Error("simulate: initial state has " + std::to_string(x0.size()) + " entries, system has " +
                std::to_string(sys.states()) + " states");
  Eigen::MatrixXd y(u.rows(), sys.outputs());
  Eigen::VectorXd x = x0;
  for (Eigen::Index k = 0; k < u.rows(); ++k) {
    const Eigen::VectorXd uk = u.row(k).transpose();
    y.row(k) = (sys.C * x + sys.D * uk).transpose();
    x = sys.A * x + sys.B * uk;
  }
  return y;
}

Eigen::MatrixXd simulate(const DiscreteSystem& sys, const Eigen::MatrixXd& u) {
  return simulate(sys, u, Eigen::VectorXd::Zero(sys.states()));
}

Eigen::VectorXcd poles(const ContinuousSystem& sys) { return linalg::eigenvalues(sys.A); }
Eigen::VectorXcd poles(const DiscreteSystem& sys) { return linalg::eigenvalues(sys.A); }

}  // namespace ambid
