#include "plant_sim/observer_controller.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "plant_sim/lqr.hpp"

namespace ambid::sim {
namespace {

using Names = std::vector<std::string>;

Eigen::Index index_of(const Names& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<Eigen::Index>(it - names.begin());
}

std::string join(const Names& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

void require_distinct(const Names& names, const char* what) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (index_of(names, names[i]) != static_cast<Eigen::Index>(i))
      throw Error(std::string(what) + " names '" + names[i] + "' twice");
}

void require_shape(const Eigen::MatrixXd& M, Eigen::Index rows, Eigen::Index cols, const char* name) {
  if (M.rows() != rows || M.cols() != cols) {
    std::ostringstream msg;
    msg << "observer controller: option " << name << " must be " << rows << "x" << cols << ", got " << M.rows() << "x"
        << M.cols();
    throw Error(msg.str());
  }
}

Eigen::MatrixXd diagonal(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const double x : values) v(i++) = x;
  return v.asDiagonal();
}

}  // namespace

ObserverControllerOptions amb1dof_observer_controller_options() {
  // LQR weights are 1 / (acceptable deviation)^2: x 10 um, x_dot 10 mm/s, currents 30 mA,
  // integral of x (in m * samples) 1e-4, inputs 1 V. At the nominal parameters and T = 1e-4 s
  // the closed loop (s = ln(z) / T) has
  //   regulator: 517 rad/s (82 Hz) with damping 0.52, 579 rad/s with damping 0.96 (position
  //              and integrator), and the common-mode current at -87.8 rad/s (real);
  //   observer:  real poles at -4.7e3, -1.3e4 and two near -5.07e4 rad/s (radius 0.8).
  // Spectral radius 0.9913 nominal and at most 0.9918 with R1, R2, kw1 or kw2 off by +-20 %.
  ObserverControllerOptions o;
  o.integral_outputs = {"x"};
  o.Q = diagonal({1.0 / (1e-5 * 1e-5), 1.0 / (1e-2 * 1e-2), 1.0 / (0.03 * 0.03), 1.0 / (0.03 * 0.03)});
  o.Q_integral = diagonal({1.0 / (1e-4 * 1e-4)});
  o.R = diagonal({1.0, 1.0});
  // Observer: position and currents measured accurately, model error mostly in the
  // velocity and current equations.
  o.W = diagonal({1e-12, 1e-6, 1e-2, 1e-2});
  o.V = diagonal({1e-12, 1e-4, 1e-4});
  o.observer_pole_radius = 0.8;
  return o;
}

StateSpaceController design_observer_controller(const ContinuousSystem& plant, double sample_time,
                                                const Names& input_names, const Names& output_names,
                                                const ObserverControllerOptions& options) {
  plant.validate();
  const Eigen::Index n = plant.states(), m = plant.inputs(), q = plant.outputs();
  if (static_cast<Eigen::Index>(input_names.size()) != m)
    throw Error("observer controller: " + std::to_string(input_names.size()) + " input names for a plant with " +
                std::to_string(m) + " inputs");
  if (static_cast<Eigen::Index>(output_names.size()) != q)
    throw Error("observer controller: " + std::to_string(output_names.size()) + " output names for a plant with " +
                std::to_string(q) + " outputs");
  Names signals = input_names;
  signals.insert(signals.end(), output_names.begin(), output_names.end());
  require_distinct(signals, "observer controller: plant inputs and outputs");
  if (!plant.D.isZero(0.0))
    throw Error(
        "observer controller: the plant must be strictly proper (D = 0) for the "
        "integrator model of seed 000 eq. 41; got ||D|| = " +
        std::to_string(plant.D.norm()));
  if (!(options.observer_pole_radius > 0.0 && options.observer_pole_radius <= 1.0))
    throw Error("observer controller: observer_pole_radius must be in (0, 1], got " +
                std::to_string(options.observer_pole_radius));

  const Eigen::Index ni = static_cast<Eigen::Index>(options.integral_outputs.size());
  require_distinct(options.integral_outputs, "observer controller: integral_outputs");
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(ni, q);
  for (Eigen::Index i = 0; i < ni; ++i) {
    const std::string& name = options.integral_outputs[static_cast<std::size_t>(i)];
    const Eigen::Index j = index_of(output_names, name);
    if (j < 0)
      throw Error("observer controller: integral output '" + name +
                  "' is not a plant output (outputs: " + join(output_names) + ")");
    E(i, j) = 1.0;
  }
  require_shape(options.Q, n, n, "Q");
  require_shape(options.Q_integral, ni, ni, "Q_integral");
  require_shape(options.R, m, m, "R");
  require_shape(options.W, n, n, "W");
  require_shape(options.V, q, q, "V");

  const DiscreteSystem d = c2d_zoh(plant, sample_time);

  // Regulator on the augmented model, eq. 41: u = -F x + Fe e = -Ka [x; e].
  Eigen::MatrixXd Aa = Eigen::MatrixXd::Identity(n + ni, n + ni);
  Aa.topLeftCorner(n, n) = d.A;
  Aa.bottomLeftCorner(ni, n) = -E * d.C * d.A;
  Eigen::MatrixXd Ba(n + ni, m);
  Ba << d.B, -E * d.C * d.B;
  Eigen::MatrixXd Qa = Eigen::MatrixXd::Zero(n + ni, n + ni);
  Qa.topLeftCorner(n, n) = options.Q;
  Qa.bottomRightCorner(ni, ni) = options.Q_integral;
  LqrGain regulator;
  try {
    regulator = dlqr(Aa, Ba, Qa, options.R);
  } catch (const Error& e) {
    throw Error(std::string("observer controller: regulator (LQR on the integrator-augmented "
                            "model, seed 000 eq. 41): ") +
                e.what());
  }
  const Eigen::MatrixXd F = regulator.K.leftCols(n);
  const Eigen::MatrixXd Fe = -regulator.K.rightCols(ni);

  // Prediction observer with all poles inside observer_pole_radius.
  const double rho = options.observer_pole_radius;
  ObserverGain observer;
  try {
    observer = predictor_gain(d.A / rho, d.C / rho, options.W, options.V);
  } catch (const Error& e) {
    throw Error(std::string("observer controller: ") + e.what());
  }
  const Eigen::MatrixXd& L = observer.L;

  StateSpaceController c;
  c.sample_time = sample_time;
  c.inputs = signals;
  c.outputs = input_names;
  c.A = Eigen::MatrixXd::Identity(n + ni, n + ni);
  c.A.topLeftCorner(n, n) = d.A - L * d.C;
  c.B = Eigen::MatrixXd::Zero(n + ni, m + q);
  c.B.topLeftCorner(n, m) = d.B;
  c.B.topRightCorner(n, q) = L;
  c.B.bottomRightCorner(ni, q) = -E;
  c.C.resize(m, n + ni);
  c.C << -F, Fe;
  c.D = Eigen::MatrixXd::Zero(m, m + q);
  c.D.rightCols(q) = -Fe * E;
  return c;
}

DiscreteSystem linear_closed_loop(const DiscreteSystem& plant, const Names& input_names, const Names& output_names,
                                  const StateSpaceController& controller) {
  plant.validate();
  const Eigen::Index n = plant.states(), m = plant.inputs(), q = plant.outputs();
  if (static_cast<Eigen::Index>(input_names.size()) != m || static_cast<Eigen::Index>(output_names.size()) != q)
    throw Error("closed loop: " + std::to_string(input_names.size()) + " input and " +
                std::to_string(output_names.size()) + " output names for a plant with " + std::to_string(m) +
                " inputs and " + std::to_string(q) + " outputs");
  controller.validate(input_names);
  if (std::abs(controller.sample_time - plant.sample_time) > 1e-9 * plant.sample_time) {
    std::ostringstream msg;
    msg << "closed loop: controller sample time " << controller.sample_time << " s differs from the plant's "
        << plant.sample_time << " s";
    throw Error(msg.str());
  }
  const Eigen::Index nc = controller.states();
  const auto nv = static_cast<Eigen::Index>(controller.inputs.size());
  const auto no = static_cast<Eigen::Index>(controller.outputs.size());

  // v = Su u + Sy y;  u = P uf + r.
  Eigen::MatrixXd Su = Eigen::MatrixXd::Zero(nv, m), Sy = Eigen::MatrixXd::Zero(nv, q);
  for (Eigen::Index k = 0; k < nv; ++k) {
    const std::string& name = controller.inputs[static_cast<std::size_t>(k)];
    const Eigen::Index iu = index_of(input_names, name), iy = index_of(output_names, name);
    if (iu >= 0) {
      Su(k, iu) = 1.0;
    } else if (iy >= 0) {
      Sy(k, iy) = 1.0;
    } else {
      throw Error("closed loop: controller input '" + name + "' is neither a plant input nor a plant output (" +
                  join(input_names) + "; " + join(output_names) + ")");
    }
  }
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(m, no);
  for (Eigen::Index k = 0; k < no; ++k)
    P(index_of(input_names, controller.outputs[static_cast<std::size_t>(k)]), k) = 1.0;

  // u = M (P Dc Sy Cp xp + P Cc xc + r),  M = (I - P Dc Sy Dp)^{-1}.
  const Eigen::MatrixXd loop = Eigen::MatrixXd::Identity(m, m) - P * controller.D * Sy * plant.D;
  const std::optional<Eigen::MatrixXd> loop_inverse = linalg::regular_inverse(loop);
  if (!loop_inverse)
    throw Error(
        "closed loop: the algebraic loop through the plant's D and the controller's D "
        "is singular (I - D_c D_p not invertible)");
  const Eigen::MatrixXd& M = *loop_inverse;
  Eigen::MatrixXd Ku(m, n + nc);
  Ku << P * controller.D * Sy * plant.C, P * controller.C;
  Ku = (M * Ku).eval();
  Eigen::MatrixXd Ky = Eigen::MatrixXd::Zero(q, n + nc);
  Ky.leftCols(n) = plant.C;
  Ky += plant.D * Ku;

  Eigen::MatrixXd Bu(n + nc, m), By = Eigen::MatrixXd::Zero(n + nc, q);
  Bu << plant.B, controller.B * Su;
  By.bottomRows(nc) = controller.B * Sy;

  DiscreteSystem cl;
  cl.sample_time = plant.sample_time;
  cl.A = Eigen::MatrixXd::Zero(n + nc, n + nc);
  cl.A.topLeftCorner(n, n) = plant.A;
  cl.A.bottomRightCorner(nc, nc) = controller.A;
  cl.A += Bu * Ku + By * Ky;
  cl.B = Bu * M + By * plant.D * M;
  cl.C.resize(q + m, n + nc);
  cl.C << Ky, Ku;
  cl.D.resize(q + m, m);
  cl.D << plant.D * M, M;
  return cl;
}

double spectral_radius(const DiscreteSystem& sys) {
  if (sys.states() == 0) return 0.0;
  return linalg::spectral_radius(sys.A);
}

}  // namespace ambid::sim
