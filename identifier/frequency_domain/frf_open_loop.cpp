#include "identifier/frequency_domain/frf_open_loop.hpp"

#include <algorithm>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "identifier/frequency_domain/frf_linalg.hpp"

namespace ambid::ident {
namespace {

double omega_of(double f) { return 2.0 * std::numbers::pi * f; }

void require_same_lines(const Frf& a, const Frf& b, const char* what) {
  if (a.lines() != b.lines() || (a.frequency_hz - b.frequency_hz).cwiseAbs().maxCoeff() >
                                    1e-9 * std::max(1.0, a.frequency_hz.cwiseAbs().maxCoeff()))
    throw Error(std::string(what) + ": the two responses are not on the same frequency lines");
}

// T_yd = T_yr M^+ (M inputs x references).
Eigen::MatrixXcd disturbance_response(const Eigen::MatrixXcd& Tyr, const Eigen::MatrixXcd& M, double f) {
  if (const double ic = inverse_condition(M); !(ic > 1e-12))
    throw InsufficientData("the references do not reach every plant input at " + std::to_string(f) + " Hz");
  return right_solve(Tyr, M);
}

}  // namespace

Eigen::MatrixXcd open_loop_from_closed_loop(const Eigen::MatrixXcd& T, const Eigen::MatrixXcd& K) {
  if (K.rows() != T.cols() || K.cols() != T.rows())
    throw Error("open loop from closed loop: K must be " + std::to_string(T.cols()) + "x" + std::to_string(T.rows()) +
                " (inputs x outputs) for T " + std::to_string(T.rows()) + "x" + std::to_string(T.cols()) + ", got " +
                std::to_string(K.rows()) + "x" + std::to_string(K.cols()));
  const Eigen::MatrixXcd X = Eigen::MatrixXcd::Identity(T.cols(), T.cols()) + K * T;
  if (const double ic = inverse_condition(X); !(ic > 1e-12))
    throw InsufficientData("open loop from closed loop: I + K T is singular (inverse condition " + std::to_string(ic) +
                           ")");
  return right_solve(T, X);
}

Frf open_loop_from_closed_loop(const Frf& Tyr, const StateSpaceController& controller, const LoopSignalNames& signals) {
  Tyr.validate();
  Frf out;
  out.frequency_hz = Tyr.frequency_hz;
  out.variance_dof = Tyr.variance_dof;
  for (Eigen::Index l = 0; l < Tyr.lines(); ++l) {
    const double f = Tyr.frequency_hz(l);
    const LoopResponse loop = loop_response(controller, signals, omega_of(f));
    const Eigen::MatrixXcd& T_r = Tyr.value[static_cast<std::size_t>(l)];
    if (T_r.rows() != static_cast<Eigen::Index>(signals.y.size()) || T_r.cols() != loop.M.cols())
      throw Error("open loop from closed loop: T_yr is " + std::to_string(T_r.rows()) + "x" +
                  std::to_string(T_r.cols()) + ", expected outputs x references " + std::to_string(signals.y.size()) +
                  "x" + std::to_string(loop.M.cols()));
    const Eigen::MatrixXcd T = disturbance_response(T_r, loop.M, f);
    Eigen::MatrixXcd G;
    try {
      G = open_loop_from_closed_loop(T, loop.K);
    } catch (const InsufficientData& e) {
      throw InsufficientData(std::string(e.what()) + " at " + std::to_string(f) + " Hz");
    }
    out.value.push_back(G);
    if (Tyr.has_variance()) {
      // dG = (I - G K) dT_yr M^+ (I + K T)^-1 = A dT_yr B.
      const Eigen::Index ny = G.rows();
      const Eigen::MatrixXcd A = Eigen::MatrixXcd::Identity(ny, ny) - G * loop.K;
      const Eigen::MatrixXcd X = Eigen::MatrixXcd::Identity(G.cols(), G.cols()) + loop.K * T;
      const Eigen::MatrixXcd Bm =
          right_solve(left_solve(loop.M, Eigen::MatrixXcd::Identity(loop.M.rows(), loop.M.rows())), X);
      const Eigen::MatrixXd a2 = A.cwiseAbs2(), b2 = Bm.cwiseAbs2();
      out.variance.push_back(a2 * Tyr.variance[static_cast<std::size_t>(l)] * b2);
    }
  }
  return out;
}

Eigen::MatrixXcd controller_from_responses(const Eigen::MatrixXcd& G, const Eigen::MatrixXcd& T) {
  if (G.rows() != G.cols() || T.rows() != G.rows() || T.cols() != G.cols())
    throw Error("controller from responses: G and T must be square and of the same size, got " +
                std::to_string(G.rows()) + "x" + std::to_string(G.cols()) + " and " + std::to_string(T.rows()) + "x" +
                std::to_string(T.cols()) + " (for a non-square plant use check_controller's loop gain)");
  if (!(inverse_condition(G) > 1e-12) || !(inverse_condition(T) > 1e-12))
    throw InsufficientData("controller from responses: G or T is singular");
  const Eigen::Index n = G.rows();
  const Eigen::MatrixXcd I = Eigen::MatrixXcd::Identity(n, n);
  return left_solve(G, I) - left_solve(T, I);
}

ControllerCheck check_controller(const Frf& plant, const Frf& Tyr, const StateSpaceController& controller,
                                 const LoopSignalNames& signals) {
  plant.validate();
  Tyr.validate();
  require_same_lines(plant, Tyr, "controller check");
  ControllerCheck out;
  out.frequency_hz = plant.frequency_hz;
  out.relative_error.resize(plant.lines());
  const bool square = plant.rows() == plant.cols();
  for (Eigen::Index l = 0; l < plant.lines(); ++l) {
    const double f = plant.frequency_hz(l);
    const LoopResponse loop = loop_response(controller, signals, omega_of(f));
    const Eigen::MatrixXcd& G = plant.value[static_cast<std::size_t>(l)];
    const Eigen::MatrixXcd T = disturbance_response(Tyr.value[static_cast<std::size_t>(l)], loop.M, f);
    if (T.rows() != G.rows() || T.cols() != G.cols())
      throw Error("controller check: the plant is " + std::to_string(G.rows()) + "x" + std::to_string(G.cols()) +
                  " but the closed loop from the plant inputs is " + std::to_string(T.rows()) + "x" +
                  std::to_string(T.cols()));
    const Eigen::Index nu = G.cols();
    const Eigen::MatrixXcd I = Eigen::MatrixXcd::Identity(nu, nu);
    const Eigen::MatrixXcd GpT = left_solve(G, T);  // (I - K G)^-1
    if (!(inverse_condition(GpT) > 1e-12))
      throw InsufficientData("controller check: G^+ T is singular at " + std::to_string(f) + " Hz");
    const Eigen::MatrixXcd L_meas = I - left_solve(GpT, I);
    const Eigen::MatrixXcd L_known = loop.K * G;
    out.loop_gain_measured.push_back(L_meas);
    out.loop_gain_known.push_back(L_known);
    out.known.push_back(loop.K);
    if (square) out.measured.push_back(controller_from_responses(G, T));
    const double scale = max_singular_value(L_known);
    out.relative_error(l) = max_singular_value(L_meas - L_known) / (scale > 0.0 ? scale : 1.0);
  }
  return out;
}

}  // namespace ambid::ident
