#include "identifier/families/amb1dof_deadbeat.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "identifier/amb1dof_structure.hpp"
#include "identifier/time_domain/closed_loop_id.hpp"
#include "identifier/time_domain/loop_signals.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;

ContinuousSystem continuous_of(const Eigen::VectorXd& p, const DiscreteSystem& like) {
  DiscreteSystem d = like;
  const Index n = like.states(), m = like.inputs();
  for (Index i = 0; i < n; ++i) {
    d.A.row(i) = p.segment(i * n, n).transpose();
    d.B.row(i) = p.segment(n * n + i * m, m).transpose();
  }
  return d2c_zoh(d);
}

double max_abs_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).cwiseAbs().maxCoeff(); }

}  // namespace

ObserverIntegralGains observer_integral_gains(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                              const Eigen::MatrixXd& C, const Eigen::MatrixXd& D, Index n, Index m) {
  const Index l = A.rows(), ni = l - n, p = B.cols() - m;
  if (ni < 0 || p < 1 || A.cols() != l || B.rows() != l || C.rows() != m || C.cols() != l || D.rows() != m ||
      D.cols() != m + p)
    throw Error("observer/integral controller: sizes A " + std::to_string(A.rows()) + "x" + std::to_string(A.cols()) +
                ", B " + std::to_string(B.rows()) + "x" + std::to_string(B.cols()) + " do not fit " +
                std::to_string(n) + " plant states and " + std::to_string(m) + " plant inputs");
  const double scale = std::max({1.0, A.cwiseAbs().maxCoeff(), B.cwiseAbs().maxCoeff()});
  const double tol = 1e-12 * scale;
  if (ni > 0) {
    if (A.bottomLeftCorner(ni, n).cwiseAbs().maxCoeff() > tol ||
        max_abs_difference(A.bottomRightCorner(ni, ni), Eigen::MatrixXd::Identity(ni, ni)) > tol ||
        A.topRightCorner(n, ni).cwiseAbs().maxCoeff() > tol)
      throw Error("observer/integral controller: A is not [A_o 0; 0 I] with " + std::to_string(ni) +
                  " integrator state(s)");
    if (B.bottomLeftCorner(ni, m).cwiseAbs().maxCoeff() > tol)
      throw Error("observer/integral controller: the integrator states read the plant input (B is not [B_o L; 0 -E])");
  }
  ObserverIntegralGains g;
  g.F = -C.leftCols(n);
  g.Fe = C.rightCols(ni);
  g.E = -B.bottomRightCorner(ni, p);
  if (D.leftCols(m).cwiseAbs().maxCoeff() != 0.0)
    throw Error("observer/integral controller: direct feedthrough from the plant input is refused");
  const Eigen::MatrixXd Dy = -g.Fe * g.E;
  if (max_abs_difference(D.rightCols(p), Dy) > 1e-9 * std::max(1.0, Dy.cwiseAbs().maxCoeff()))
    throw Error("observer/integral controller: D is not [0 -Fe E] (the integrators are not e[k] = e[k-1] - E y[k])");
  return g;
}

Amb1dofIdentification identify_amb1dof_deadbeat(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                                                const Eigen::MatrixXd& uf, const ObserverIntegralGains& gains,
                                                const Eigen::VectorXd& integrator_initial, double sample_time,
                                                double L1, double L2, double m, const DeadbeatOptions& options) {
  if (y.cols() != 3 || u.cols() != 2)
    throw Error("amb1dof deadbeat identification: needs y = [x, i1, i2] and u = [u1, u2], got " +
                std::to_string(y.cols()) + " and " + std::to_string(u.cols()) + " columns");
  for (const double v : {L1, L2, m})
    if (!(v > 0.0) || !std::isfinite(v))
      throw Error("amb1dof deadbeat identification: L1, L2 and m must be positive, got " + std::to_string(v));
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, 4);
  C(0, 0) = 1.0;
  C(1, 2) = 1.0;
  C(2, 3) = 1.0;
  Amb1dofIdentification out;
  const Eigen::MatrixXd e = integrator_states(y, gains.E, integrator_initial);
  out.realization = deadbeat_realization(y, u, uf, e, C, gains.F, gains.Fe, sample_time, options);
  const DiscreteSystem& d = out.realization.system;
  out.continuous = d2c_zoh(d);
  const Eigen::Matrix<double, 9, 1> v = amb1dof_structure_vector(out.continuous);
  out.structure_deviation = amb1dof_structure_deviation(out.continuous);

  // First-order propagation of the covariance of p = [A rows, B rows] through d2c and eq. (4).
  const Index n = 4, mi = 2, np = n * (n + mi);
  Eigen::VectorXd p(np);
  for (Index i = 0; i < n; ++i) {
    p.segment(i * n, n) = d.A.row(i).transpose();
    p.segment(n * n + i * mi, mi) = d.B.row(i).transpose();
  }
  const double a_scale = d.A.cwiseAbs().maxCoeff(), b_scale = d.B.cwiseAbs().maxCoeff();
  Eigen::MatrixXd J(9, np);
  for (Index j = 0; j < np; ++j) {
    const double typical = j < n * n ? a_scale : b_scale;
    const double h = 1e-6 * std::max(std::abs(p(j)), 1e-3 * typical);
    Eigen::VectorXd plus = p, minus = p;
    plus(j) += h;
    minus(j) -= h;
    J.col(j) = (amb1dof_structure_vector(continuous_of(plus, d)) - amb1dof_structure_vector(continuous_of(minus, d))) /
               (2.0 * h);
  }
  out.parameter_covariance = J * out.realization.parameter_covariance * J.transpose();

  const Eigen::Matrix<double, 9, 1> scale = amb1dof_physical_scale(L1, L2, m);
  const std::vector<std::string>& kV = amb1dof_structure_names();
  const std::vector<std::string>& physical_of_v = amb1dof_physical_names();
  for (Index i = 0; i < 9; ++i) {
    const double sigma = std::sqrt(std::max(0.0, out.parameter_covariance(i, i)));
    out.parameters[kV[static_cast<std::size_t>(i)]] = v(i);
    out.parameter_uncertainty[kV[static_cast<std::size_t>(i)]] = sigma;
    out.physical[physical_of_v[static_cast<std::size_t>(i)]] = v(i) * scale(i);
    out.physical_uncertainty[physical_of_v[static_cast<std::size_t>(i)]] = sigma * scale(i);
  }
  return out;
}

Amb1dofIdentification identify_amb1dof_deadbeat(const Experiment& e, const DeadbeatOptions& options) {
  if (e.plant.model != "amb1dof_voltage")
    throw Error("amb1dof deadbeat identification: plant.model is '" + e.plant.model + "', expected 'amb1dof_voltage'");
  if (!e.controller)
    throw Error("amb1dof deadbeat identification: the experiment has no controller (it must be known)");
  const std::vector<std::string> un = {"u1", "u2"}, yn = {"x", "i1", "i2"};
  const LoopSignals s = loop_signals(e, yn, un, "amb1dof deadbeat identification");
  const KnownController k = known_controller(*e.controller, un, yn);
  const ObserverIntegralGains gains = observer_integral_gains(k.A, k.B, k.C, k.D, 4, 2);
  const Amb1dofNominal nominal = amb1dof_nominal(e, "amb1dof deadbeat identification");
  Eigen::VectorXd s0;
  const Eigen::VectorXd& xc0 = e.controller->initial_state;
  if (xc0.size() != 0) {
    if (xc0.size() != k.A.rows())
      throw Error("amb1dof deadbeat identification: controller.initial_state has " + std::to_string(xc0.size()) +
                  " entries, the controller " + std::to_string(k.A.rows()) + " states");
    s0 = xc0.tail(gains.E.rows());
  }
  return identify_amb1dof_deadbeat(s.y, s.u, s.uf, gains, s0, e.sample_time, nominal.L1, nominal.L2, nominal.m,
                                   options);
}

}  // namespace ambid::ident
