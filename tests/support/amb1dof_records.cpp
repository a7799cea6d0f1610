#include "support/amb1dof_records.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "plant_sim/amb1dof_physical.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/closed_loop.hpp"
#include "plant_sim/excitation.hpp"
#include "plant_sim/observer_controller.hpp"
#include "plant_sim/plant.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::test_support {
namespace amb1dof_records {

Eigen::MatrixXd diagonal(std::initializer_list<double> values) {
  Eigen::VectorXd d(Eigen::Index(values.size()));
  Eigen::Index i = 0;
  for (const double v : values) d(i++) = v;
  return d.asDiagonal();
}

sim::Scenario scenario_of(const Amb1dofRecordOptions& o, bool excited) {
  const std::vector<std::string>& known = amb1dof_record_controllers();
  if (std::find(known.begin(), known.end(), o.controller) == known.end())
    throw Error("amb1dof records: unknown controller '" + o.controller + "' (known: lqr, pid, leadlag, observer)");
  sim::ScenarioOptions s;
  s.controller = o.controller == "observer" ? "lqr" : o.controller;  // observer: lqr's loop, other weights
  s.true_parameters = o.true_parameters;
  s.sample_time = o.sample_time;
  s.duration = o.settle + o.duration;
  s.seed = o.seed;
  if (excited) {
    s.amplitude = o.amplitude;
    s.excitation = o.excitation;
    s.f_min = o.f_min;
    s.f_max = o.f_max;
    s.position_noise = o.position_noise;
    s.current_noise = o.current_noise;
  } else {
    s.excitation = "none";
    s.duration = std::max(s.duration, 1.0);  // the slowest settling (the PID's integral) is ~50 ms
  }
  sim::Scenario scenario = sim::build_scenario(s);
  if (o.controller == "observer") {
    const sim::Amb1dofVoltage nominal(sim::Amb1dofParameters::nominal());
    scenario.header.controller = sim::design_observer_controller(
        nominal.linearize(), o.sample_time, scenario.header.u_names, scenario.header.y_names, other_observer_options());
  }
  const int divider = o.clock_divider;
  if (divider < 1) throw Error("amb1dof records: clock_divider must be >= 1, got " + std::to_string(divider));
  if (excited && o.excitation == "prbs" && divider > 1) {
    sim::PrbsOptions p;
    const Eigen::Index samples = scenario.options.samples;
    p.clock_divider = divider;
    p.register_length = std::clamp(int(std::ceil(std::log2(double(samples / divider) + 1.0))), 6, 24);
    p.amplitude = o.amplitude;
    p.seed = o.seed;
    p.channels = 2;
    sim::Excitation e = sim::prbs(p, samples, o.sample_time);
    scenario.options.excitation = std::move(e.samples);
    scenario.header.extra.json()["excitation"] = std::move(e.description.json());
  }
  scenario.options.substeps = o.substeps;
  return scenario;
}

// The true parameters of `o`'s loop and where it comes to rest: the same loop without
// excitation or noise, run to its end.
sim::Amb1dofParameters rest_parameters(const Amb1dofRecordOptions& o) {
  const sim::Scenario rest = scenario_of(o, false);
  const Experiment settled = sim::run_closed_loop(*rest.truth, rest.header, rest.options);
  const Eigen::RowVectorXd last = settled.y.bottomRows(1);
  if (!(std::abs(last(0)) < 1e-10) || !(std::abs(last(1) - last(2)) < 1e-8 * last(1)))
    throw Error("amb1dof records: the '" + o.controller + "' loop has not come to rest at x = 0, i1 = i2 (x = " +
                std::to_string(last(0)) + " m, i1 - i2 = " + std::to_string(last(1) - last(2)) + " A)");
  sim::Amb1dofParameters p = sim::Amb1dofParameters::nominal();
  for (const auto& [name, value] : o.true_parameters) p.set(name, value);
  p.i0 = last(1);
  return p;
}

// One plant until sample `step` (counted by advance, which the closed-loop runner calls once per
// sample), another from there on: a fault that changes the plant while the loop runs.
class SteppedAmb1dofPlant final : public sim::Plant {
 public:
  SteppedAmb1dofPlant(std::unique_ptr<sim::Plant> before, std::unique_ptr<sim::Plant> after, Eigen::Index step)
      : before_(std::move(before)), after_(std::move(after)), step_(step) {}
  std::string model() const override { return before_->model(); }
  std::vector<std::string> state_names() const override { return before_->state_names(); }
  std::vector<std::string> input_names() const override { return before_->input_names(); }
  std::vector<std::string> output_names() const override { return before_->output_names(); }
  std::vector<std::string> disturbance_names() const override { return before_->disturbance_names(); }
  Eigen::VectorXd derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& w) const override {
    return current().derivative(x, u, w);
  }
  Eigen::VectorXd output(const Eigen::VectorXd& x) const override { return current().output(x); }
  void output_into(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override { current().output_into(x, y); }
  void advance(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w, double sample_time,
               int substeps) const override {
    current().advance(x, u, w, sample_time, substeps);
    ++advanced_;
  }
  Eigen::VectorXd equilibrium_state() const override { return before_->equilibrium_state(); }
  Eigen::VectorXd equilibrium_input() const override { return before_->equilibrium_input(); }

 private:
  const sim::Plant& current() const { return advanced_ < step_ ? *before_ : *after_; }
  std::unique_ptr<sim::Plant> before_, after_;
  Eigen::Index step_;
  mutable Eigen::Index advanced_ = 0;
};

}  // namespace amb1dof_records
using namespace amb1dof_records;

sim::ObserverControllerOptions other_observer_options() {
  sim::ObserverControllerOptions o;
  o.integral_outputs = {"x"};
  o.Q = diagonal({1.0 / (2e-5 * 2e-5), 1.0 / (2e-2 * 2e-2), 1.0 / (0.05 * 0.05), 1.0 / (0.05 * 0.05)});
  o.Q_integral = diagonal({1.0 / (3e-4 * 3e-4)});
  o.R = diagonal({1.0, 1.0});
  o.W = diagonal({1e-12, 1e-5, 1e-3, 1e-3});
  o.V = diagonal({1e-12, 1e-4, 1e-4});
  o.observer_pole_radius = 0.9;
  return o;
}

int prbs_clock_divider(const std::string& controller) {
  return controller == "pid" || controller == "leadlag" ? 30 : 1;
}

const std::vector<std::string>& amb1dof_record_controllers() {
  static const std::vector<std::string> names = {"lqr", "pid", "leadlag", "observer"};
  return names;
}

Amb1dofRecord simulate_amb1dof_record(const Amb1dofRecordOptions& o) {
  Amb1dofRecord record;
  record.true_parameters = rest_parameters(o);
  record.truth = sim::amb1dof_structure_parameters(record.true_parameters);
  record.settled = Eigen::Index(std::llround(o.settle / o.sample_time));

  sim::Scenario excited = scenario_of(o, true);
  if (!o.step_parameters.empty()) {
    record.stepped = record.settled + Eigen::Index(std::llround(o.step_time / o.sample_time));
    if (!(o.step_time > 0.0) || record.stepped >= excited.options.samples)
      throw Error("amb1dof records: step_time must be within the record after the settling, got " +
                  std::to_string(o.step_time) + " s");
    Amb1dofRecordOptions after = o;
    for (const auto& [name, value] : o.step_parameters) after.true_parameters[name] = value;
    record.true_parameters_after_step = rest_parameters(after);
    record.truth_after_step = sim::amb1dof_structure_parameters(record.true_parameters_after_step);
    excited.truth = std::make_unique<SteppedAmb1dofPlant>(std::move(excited.truth),
                                                          std::move(scenario_of(after, true).truth), record.stepped);
  }
  record.experiment = sim::run_closed_loop(*excited.truth, excited.header, excited.options);
  return record;
}

}  // namespace ambid::test_support
