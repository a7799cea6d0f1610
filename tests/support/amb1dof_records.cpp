#include "support/amb1dof_records.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "plant_sim/amb1dof_physical.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/closed_loop.hpp"
#include "plant_sim/excitation.hpp"
#include "plant_sim/observer_controller.hpp"
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
  // The rest point: the same loop without excitation or noise, run to its end.
  const sim::Scenario rest = scenario_of(o, false);
  const Experiment settled = sim::run_closed_loop(*rest.truth, rest.header, rest.options);
  const Eigen::RowVectorXd last = settled.y.bottomRows(1);
  if (!(std::abs(last(0)) < 1e-10) || !(std::abs(last(1) - last(2)) < 1e-8 * last(1)))
    throw Error("amb1dof records: the '" + o.controller + "' loop has not come to rest at x = 0, i1 = i2 (x = " +
                std::to_string(last(0)) + " m, i1 - i2 = " + std::to_string(last(1) - last(2)) + " A)");
  record.true_parameters = sim::Amb1dofParameters::nominal();
  for (const auto& [name, value] : o.true_parameters) record.true_parameters.set(name, value);
  record.true_parameters.i0 = last(1);
  record.truth = sim::amb1dof_structure_parameters(record.true_parameters);

  const sim::Scenario excited = scenario_of(o, true);
  record.experiment = sim::run_closed_loop(*excited.truth, excited.header, excited.options);
  record.settled = Eigen::Index(std::llround(o.settle / o.sample_time));
  return record;
}

}  // namespace ambid::test_support
