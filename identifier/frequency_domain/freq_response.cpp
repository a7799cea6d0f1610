#include "identifier/frequency_domain/freq_response.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {
namespace {

using cd = std::complex<double>;

// C (z I - A)^-1 B + D; `where` names the point for the error message.
Eigen::MatrixXcd resolvent_response(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                                    const Eigen::MatrixXd& D, cd z, const std::string& where) {
  const Eigen::Index n = A.rows();
  if (n == 0) return D.cast<cd>();
  Eigen::MatrixXcd M = -A.cast<cd>();
  M.diagonal().array() += z;
  const linalg::ConditionedSolution<Eigen::MatrixXcd> resolvent = linalg::lu_solve(M, B.cast<cd>());
  // rcond is an estimate; a pole on the evaluation point gives rcond ~ eps or a non-finite
  // solution.
  if (!(resolvent.rcond > 1e-13))
    throw Error("frequency response: the system has a pole at " + where + " (the response is infinite)");
  Eigen::MatrixXcd out = C.cast<cd>() * resolvent.x + D.cast<cd>();
  if (!out.allFinite()) throw Error("frequency response: not finite at " + where);
  return out;
}

void require_omega(double omega) {
  if (!std::isfinite(omega))
    throw Error("frequency response: angular frequency must be finite, got " + std::to_string(omega));
}

std::string omega_text(double omega) {
  return "w = " + std::to_string(omega) + " rad/s (" + std::to_string(omega / (2.0 * std::numbers::pi)) + " Hz)";
}

template <class System>
Frf grid_response(const System& sys, const Eigen::VectorXd& frequency_hz) {
  Frf out;
  out.frequency_hz = frequency_hz;
  out.value.reserve(static_cast<std::size_t>(frequency_hz.size()));
  for (Eigen::Index k = 0; k < frequency_hz.size(); ++k)
    out.value.push_back(freq_response(sys, 2.0 * std::numbers::pi * frequency_hz(k)));
  return out;
}

}  // namespace

Eigen::MatrixXcd freq_response(const ContinuousSystem& sys, double omega) {
  sys.validate();
  require_omega(omega);
  return resolvent_response(sys.A, sys.B, sys.C, sys.D, cd(0.0, omega), omega_text(omega));
}

Eigen::MatrixXcd freq_response(const DiscreteSystem& sys, double omega) {
  sys.validate();
  require_omega(omega);
  return resolvent_response(sys.A, sys.B, sys.C, sys.D, std::polar(1.0, omega * sys.sample_time), omega_text(omega));
}

Eigen::MatrixXcd freq_response(const StateSpaceController& controller, double omega) {
  require_omega(omega);
  if (!(controller.sample_time > 0.0) || !std::isfinite(controller.sample_time))
    throw Error("controller frequency response: sample_time must be positive, got " +
                std::to_string(controller.sample_time));
  const Eigen::Index n = controller.A.rows();
  const auto ni = static_cast<Eigen::Index>(controller.inputs.size());
  const auto no = static_cast<Eigen::Index>(controller.outputs.size());
  if (controller.A.cols() != n || controller.B.rows() != n || controller.B.cols() != ni || controller.C.rows() != no ||
      controller.C.cols() != n || controller.D.rows() != no || controller.D.cols() != ni)
    throw Error("controller frequency response: matrices do not match " + std::to_string(n) + " states, " +
                std::to_string(ni) + " inputs, " + std::to_string(no) + " outputs");
  return resolvent_response(controller.A, controller.B, controller.C, controller.D,
                            std::polar(1.0, omega * controller.sample_time), omega_text(omega));
}

Frf freq_response(const ContinuousSystem& sys, const Eigen::VectorXd& frequency_hz) {
  return grid_response(sys, frequency_hz);
}

Frf freq_response(const DiscreteSystem& sys, const Eigen::VectorXd& frequency_hz) {
  return grid_response(sys, frequency_hz);
}

}  // namespace ambid::ident
