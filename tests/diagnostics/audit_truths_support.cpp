#include "audit_truths.hpp"

#include <cmath>
#include <memory>
#include <numbers>

#include "core/error.hpp"
#include "plant_sim/amb1dof_extended.hpp"
#include "plant_sim/closed_loop.hpp"
#include "plant_sim/scenario.hpp"
#include "support/amb1dof_records.hpp"

namespace ambid::diag::testing {
namespace audit_truths_support {

constexpr double kPositionNoise = 1e-7, kCurrentNoise = 1e-3, kForceNoise = 0.005, kNoiseLag = 3e-4;
constexpr int kSubsteps = 20;

// Amb1dofExtended with what the catalogue cannot express, as extra states after its own:
// a clock t (for the varying gain), a second mode q2, q2_dot, and the coloured sensor noise n
// (n' = (w_n - n) / lag, w_n a second disturbance held per sample).
class OutOfCatalogueBearing : public sim::Plant {
 public:
  OutOfCatalogueBearing(const sim::Amb1dofParameters& p, const TruthOptions& o)
      : inner_(p, o.effects), o_(o), n_(Eigen::Index(inner_.state_names().size())) {}

  std::string model() const override { return inner_.model(); }
  std::vector<std::string> state_names() const override {
    auto names = inner_.state_names();
    names.insert(names.end(), {"t", "q2", "q2_dot", "n_x"});
    return names;
  }
  std::vector<std::string> input_names() const override { return inner_.input_names(); }
  std::vector<std::string> output_names() const override { return inner_.output_names(); }
  std::vector<std::string> disturbance_names() const override { return {"Fz", "n_x_drive"}; }

  Eigen::VectorXd derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& w) const override {
    Eigen::VectorXd v = u;
    const double t = x[n_];
    v[0] *= 1.0 + o_.gain_variation * std::sin(2.0 * std::numbers::pi * o_.gain_variation_hz * t);
    Eigen::VectorXd out(x.size());
    out.head(n_) = inner_.derivative(x.head(n_), v, w.head(1));
    const double omega = 2.0 * std::numbers::pi * (o_.second_mode_f > 0 ? o_.second_mode_f : 1.0);
    out[n_] = 1.0;
    out[n_ + 1] = x[n_ + 2];
    out[n_ + 2] = o_.second_mode_f > 0 ? -2.0 * o_.second_mode_zeta * omega * x[n_ + 2] - omega * omega * x[n_ + 1] +
                                             o_.second_mode_coupling * out[1]
                                       : 0.0;
    out[n_ + 3] = (w[1] - x[n_ + 3]) / kNoiseLag;
    return out;
  }
  Eigen::VectorXd output(const Eigen::VectorXd& x) const override {
    Eigen::VectorXd y = inner_.output(x.head(n_));
    y[0] += x[n_ + 1] + x[n_ + 3];
    return y;
  }
  Eigen::VectorXd equilibrium_state() const override {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n_ + 4);
    x.head(n_) = inner_.equilibrium_state();
    return x;
  }
  Eigen::VectorXd equilibrium_input() const override { return inner_.equilibrium_input(); }

 private:
  sim::Amb1dofExtended inner_;
  TruthOptions o_;
  Eigen::Index n_;
};

}  // namespace audit_truths_support
using namespace audit_truths_support;

Experiment simulate_truth(const TruthOptions& o) {
  const bool beyond = o.second_mode_f > 0.0 || o.gain_variation != 0.0 || o.coloured_noise;
  if (beyond)
    for (const auto& e : o.effects)
      if (e.name == "sensor_delay")
        throw Error("simulate_truth: sensor_delay needs the plant's own stepper, not the out-of-catalogue one");
  sim::ScenarioOptions s;
  s.controller = o.controller;
  s.true_parameters = o.parameters;
  s.effects = o.effects;
  // Most of a PRBS's power lies where the coils' inductance (0.43 H) leaves mA of current:
  // a multisine of 1 V rms up to 800 Hz moves the currents by tens of mA.
  s.excitation = "multisine";
  s.f_min = 2.0;
  s.f_max = 800.0;
  s.amplitude = 1.0;
  s.duration = o.duration;
  s.seed = o.seed;
  s.position_noise = o.coloured_noise ? 0.0 : audit_truths_support::kPositionNoise;
  s.current_noise = audit_truths_support::kCurrentNoise;
  s.force_noise = kForceNoise;
  sim::Scenario scenario = sim::build_scenario(s);
  scenario.options.substeps = kSubsteps;
  if (!beyond) return sim::run_closed_loop(*scenario.truth, scenario.header, scenario.options);
  sim::Amb1dofParameters p = sim::Amb1dofParameters::nominal();
  for (const auto& [name, value] : o.parameters) p.set(name, value);
  const OutOfCatalogueBearing truth(p, o);
  // Held per sample, w_n of variance s^2 gives n a variance of about s^2 dt / (2 lag).
  const double drive = audit_truths_support::kPositionNoise * std::sqrt(2.0 * kNoiseLag / s.sample_time);
  scenario.options.process_noise_std = Eigen::Vector2d(kForceNoise, o.coloured_noise ? drive : 0.0);
  scenario.options.measurement_noise_std =
      Eigen::Vector3d(s.position_noise, audit_truths_support::kCurrentNoise, audit_truths_support::kCurrentNoise);
  return sim::run_closed_loop(truth, scenario.header, scenario.options);
}

Experiment independent_clean(const std::string& controller, std::uint64_t seed, double duration) {
  test_support::Amb1dofRecordOptions o;
  o.controller = controller;
  o.amplitude = 1.0;
  o.duration = duration;
  o.settle = 0.1;
  o.position_noise = audit_truths_support::kPositionNoise;
  o.current_noise = audit_truths_support::kCurrentNoise;
  o.seed = seed;
  return test_support::simulate_amb1dof_record(o).experiment;
}

}  // namespace ambid::diag::testing
