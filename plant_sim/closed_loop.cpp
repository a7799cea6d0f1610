#include "plant_sim/closed_loop.hpp"

#include <algorithm>
#include <random>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "plant_sim/integrator.hpp"

namespace ambid::sim {
namespace {

std::string join_signals(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// Where each controller input comes from at sample k.
enum class Source { output, input, excitation };
struct InputRoute {
  Source source;
  Eigen::Index index;
};

InputRoute route_of(const std::string& name, const Experiment& header) {
  auto find = [&](const std::vector<std::string>& names) {
    return std::find(names.begin(), names.end(), name) - names.begin();
  };
  if (auto i = find(header.y_names); i < std::ssize(header.y_names)) return {Source::output, i};
  if (auto i = find(header.u_names); i < std::ssize(header.u_names)) return {Source::input, i};
  if (auto i = find(header.r_names); i < std::ssize(header.r_names)) return {Source::excitation, i};
  throw Error("closed loop: controller input '" + name +
              "' is not a signal of the experiment (y: " + join_signals(header.y_names) +
              "; u: " + join_signals(header.u_names) + "; r: " + join_signals(header.r_names) + ")");
}

void check_names(const char* what, const std::vector<std::string>& header_names,
                 const std::vector<std::string>& plant_names) {
  if (header_names != plant_names)
    throw Error(std::string("closed loop: experiment ") + what + " signals (" + join_signals(header_names) +
                ") must be the plant's (" + join_signals(plant_names) + ")");
}

void check_size(const char* what, const Eigen::VectorXd& v, Eigen::Index expected) {
  if (v.size() != 0 && v.size() != expected)
    throw Error(std::string("closed loop: ") + what + " has " + std::to_string(v.size()) + " entries, expected " +
                std::to_string(expected));
  if (v.size() != 0 && !v.allFinite()) throw Error(std::string("closed loop: ") + what + " is not finite");
}

// Controller input j takes signal `signal` (an index into y, u or r).
struct Route {
  Eigen::Index input, signal;
};

// The sample loop with its buffers allocated once: run() allocates nothing per sample. Its
// template arguments are the controller's states, inputs and outputs (Eigen::Dynamic for any).
struct Loop {
  const Plant& truth;
  const ClosedLoopOptions& options;
  int substeps;
  double dt;
  bool excited, limited;
  const Eigen::VectorXd &lower, &upper;
  const std::vector<Limit>& state_limits;  // controller.state_limits (deviations); empty: none
  std::vector<Route> from_output{}, from_input{}, from_excitation{};
  Eigen::VectorXd y_op{}, u_op{}, r_op{};
  Eigen::VectorXd x{};  // plant state, starts at the operating point

  // What the controller reads of output i at sample k when the plant puts out `value`
  // (ClosedLoopOptions::followed).
  double read(Eigen::Index k, Eigen::Index i, double value) const {
    if (options.followed_resolution.size() == 0 || !(options.followed_resolution(i) > 0.0)) return value;
    const double logged = options.followed(k, i), half = 0.5 * options.followed_resolution(i);
    return value > logged + half ? value - half : value < logged - half ? value + half : logged;
  }

  // Fills out.t, y, u, r; returns the number of saturated samples.
  template <int NC, int NV, int NU>
  Eigen::Index run(const StateSpaceController& ctrl, Experiment& out) {
    using StateVector = Eigen::Matrix<double, NC, 1>;
    const Eigen::Matrix<double, NC, NC> A = ctrl.A;
    const Eigen::Matrix<double, NC, NV> B = ctrl.B;
    const Eigen::Matrix<double, NU, NC> C = ctrl.C;
    const Eigen::Matrix<double, NU, NV> D = ctrl.D;
    StateVector xc =
        ctrl.initial_state.size() ? StateVector(ctrl.initial_state) : StateVector(StateVector::Zero(ctrl.states()));
    StateVector xc_next(xc.size());
    Eigen::Matrix<double, NV, 1> v = Eigen::Matrix<double, NV, 1>::Zero(B.cols());
    Eigen::Matrix<double, NU, 1> du(C.rows()), u_cmd(C.rows());
    Eigen::VectorXd y(out.y.cols()), u_applied(C.rows());
    Eigen::VectorXd w = Eigen::VectorXd::Zero(std::ssize(truth.disturbance_names()));

    std::mt19937_64 rng(options.seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    const bool measurement_noise = options.measurement_noise_std.size() != 0;
    const bool process_noise = options.process_noise_std.size() != 0;
    Eigen::Index saturated = 0;
    for (Eigen::Index k = 0; k < out.t.size(); ++k) {
      truth.output_into(x, y);
      if (measurement_noise)
        for (Eigen::Index i = 0; i < y.size(); ++i) y(i) += options.measurement_noise_std(i) * normal(rng);

      // uf = C xc + D v needs v, whose u entries need uf: D has zero u columns (validated), so
      // evaluate uf with those entries zero, then fill them in for the state update.
      for (const auto [j, i] : from_output) v(j) = read(k, i, y(i)) - y_op(i);
      for (const auto [j, i] : from_excitation) v(j) = options.excitation(k, i);
      for (const auto [j, i] : from_input) v(j) = 0.0;
      du.noalias() = C * xc + D * v;
      if (excited) du += options.excitation.row(k).transpose();
      for (const auto [j, i] : from_input) v(j) = du(i);

      out.t(k) = double(k) * dt;
      out.y.row(k) = y.transpose();
      u_cmd = u_op + du;
      out.u.row(k) = u_cmd.transpose();
      if (excited) out.r.row(k) = (r_op + options.excitation.row(k).transpose()).transpose();

      bool clamped = false;
      if (limited) {
        u_applied = u_cmd.cwiseMax(lower).cwiseMin(upper);
        clamped = (u_applied.array() != u_cmd.array()).any();
      } else {
        u_applied = u_cmd;
      }
      if (process_noise)
        for (Eigen::Index i = 0; i < w.size(); ++i) w(i) = options.process_noise_std(i) * normal(rng);
      try {
        truth.advance(x, u_applied, w, dt, substeps);
      } catch (const Error& e) {
        std::ostringstream msg;
        msg << "closed loop: at t = " << out.t(k) << " s: " << e.what();
        throw Error(msg.str());
      }
      if (!x.allFinite()) {
        std::ostringstream msg;
        msg << "closed loop: the plant state became non-finite at t = " << out.t(k) << " s (unstable loop?)";
        throw Error(msg.str());
      }
      xc_next.noalias() = A * xc + B * v;
      for (std::size_t i = 0; i < state_limits.size(); ++i) {  // anti-windup clamps
        const double free = xc_next(Eigen::Index(i));
        xc_next(Eigen::Index(i)) = std::clamp(free, state_limits[i].lo, state_limits[i].hi);
        if (xc_next(Eigen::Index(i)) != free) clamped = true;
      }
      xc = xc_next;
      if (clamped) ++saturated;
    }
    return saturated;
  }
};

}  // namespace

Experiment run_closed_loop(const Plant& truth, const Experiment& header, const ClosedLoopOptions& options,
                           ClosedLoopStatistics* statistics) {
  if (!header.controller) throw Error("closed loop: the experiment has no controller");
  const StateSpaceController& ctrl = *header.controller;
  ctrl.validate(header.u_names);
  check_names("y", header.y_names, truth.output_names());
  check_names("u", header.u_names, truth.input_names());
  if (ctrl.outputs != header.u_names)
    throw Error("closed loop: controller outputs (" + join_signals(ctrl.outputs) + ") must be the plant inputs (" +
                join_signals(header.u_names) + ")");
  const double dt = header.sample_time;
  if (!(dt > 0.0)) throw Error("closed loop: sample_time must be positive, got " + std::to_string(dt));
  if (std::abs(ctrl.sample_time - dt) > 1e-9 * dt)
    throw Error("closed loop: controller sample_time " + std::to_string(ctrl.sample_time) +
                " differs from the experiment's " + std::to_string(dt));
  if (options.samples < 1)
    throw Error("closed loop: samples must be at least 1, got " + std::to_string(options.samples));

  const Eigen::Index ny = std::ssize(header.y_names), nu = std::ssize(header.u_names);
  const Eigen::Index nw = std::ssize(truth.disturbance_names());
  const Eigen::Index nr = std::ssize(header.r_names), N = options.samples;
  const bool excited = options.excitation.size() != 0;
  if (excited != (nr != 0))
    throw Error("closed loop: excitation given for " + std::to_string(nr) +
                " named excitation signals; give both or neither");
  if (excited && (options.excitation.rows() != N || options.excitation.cols() != nu || nr != nu))
    throw Error("closed loop: excitation must be " + std::to_string(N) + "x" + std::to_string(nu) +
                " (samples x plant inputs) with one r name per input, got " +
                std::to_string(options.excitation.rows()) + "x" + std::to_string(options.excitation.cols()));
  if (excited && !options.excitation.allFinite()) throw Error("closed loop: excitation is not finite");
  check_size("measurement_noise_std", options.measurement_noise_std, ny);
  check_size("process_noise_std", options.process_noise_std, nw);
  check_size("input_lower", options.input_lower, nu);
  check_size("input_upper", options.input_upper, nu);
  check_size("followed_resolution", options.followed_resolution, ny);
  if ((options.followed_resolution.size() != 0) != (options.followed.size() != 0) ||
      (options.followed.size() != 0 &&
       (options.followed.rows() < N || options.followed.cols() != ny || !options.followed.allFinite() ||
        (options.followed_resolution.array() < 0.0).any())))
    throw Error("closed loop: a followed record needs at least " + std::to_string(N) + " finite rows of " +
                std::to_string(ny) + " outputs and a resolution >= 0 per output, got " +
                std::to_string(options.followed.rows()) + "x" + std::to_string(options.followed.cols()) + " and " +
                std::to_string(options.followed_resolution.size()) + " resolutions");
  const bool limited =
      options.input_lower.size() != 0 || options.input_upper.size() != 0 || !ctrl.output_limits.empty();
  Eigen::VectorXd lower = options.input_lower.size() ? options.input_lower : Eigen::VectorXd::Constant(nu, -INFINITY);
  Eigen::VectorXd upper = options.input_upper.size() ? options.input_upper : Eigen::VectorXd::Constant(nu, INFINITY);
  // controller.output_limits clamp the plant input too (outputs are the u signals, in order).
  for (std::size_t j = 0; j < ctrl.output_limits.size(); ++j) {
    lower(Eigen::Index(j)) = std::max(lower(Eigen::Index(j)), ctrl.output_limits[j].lo);
    upper(Eigen::Index(j)) = std::min(upper(Eigen::Index(j)), ctrl.output_limits[j].hi);
  }
  const int substeps = options.substeps > 0 ? options.substeps : kDefaultSubsteps;

  Loop loop{truth, options, substeps, dt, excited, limited, lower, upper, ctrl.state_limits};
  for (std::size_t j = 0; j < ctrl.inputs.size(); ++j) {
    const InputRoute route = route_of(ctrl.inputs[j], header);
    auto& target = route.source == Source::output  ? loop.from_output
                   : route.source == Source::input ? loop.from_input
                                                   : loop.from_excitation;
    target.push_back({Eigen::Index(j), route.index});
  }
  loop.y_op = header.operating_values(header.y_names);
  loop.u_op = header.operating_values(header.u_names);
  loop.r_op = header.operating_values(header.r_names);

  // Start at the nominal operating point: named states take their operating value.
  loop.x = truth.equilibrium_state();
  const auto state_names = truth.state_names();
  for (std::size_t i = 0; i < state_names.size(); ++i)
    if (header.operating_point.count(state_names[i]))
      loop.x(Eigen::Index(i)) = header.operating_point.at(state_names[i]);

  Experiment out = header;
  out.t.resize(N);
  out.y.resize(N, ny);
  out.u.resize(N, nu);
  out.r.resize(excited ? N : 0, nr);
  const Eigen::Index nc = ctrl.states(), nv = std::ssize(ctrl.inputs);
  // The observer controller of amb1dof_voltage (4 + 1 states; inputs u1, u2, x, i1, i2) runs
  // with fixed-size matrices; any other controller with dynamic ones.
  const Eigen::Index saturated = nc == 5 && nv == 5 && nu == 2
                                     ? loop.run<5, 5, 2>(ctrl, out)
                                     : loop.run<Eigen::Dynamic, Eigen::Dynamic, Eigen::Dynamic>(ctrl, out);
  if (statistics) statistics->saturated_samples = saturated;
  return out;
}

}  // namespace ambid::sim
