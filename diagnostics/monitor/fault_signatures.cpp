#include "diagnostics/fault_signatures.hpp"

#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "diagnostics/fault_isolation.hpp"
#include "identifier/amb1dof_structure.hpp"
#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/amb1dof_physical.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/closed_loop.hpp"
#include "plant_sim/linearize.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::diag {
namespace {

// The true plant as the loop sees it: the position sensor reads gain * x, and the plant is
// linearised at the operating point the loop settled at rather than the nominal one.
class SensedPlant : public sim::Plant {
 public:
  SensedPlant(const sim::Amb1dofParameters& parameters, double gain)
      : plant_(parameters), gain_(gain), state_(plant_.equilibrium_state()), input_(plant_.equilibrium_input()) {}

  std::string model() const override { return plant_.model(); }
  std::vector<std::string> state_names() const override { return plant_.state_names(); }
  std::vector<std::string> input_names() const override { return plant_.input_names(); }
  std::vector<std::string> output_names() const override { return plant_.output_names(); }
  std::vector<std::string> disturbance_names() const override { return plant_.disturbance_names(); }
  Eigen::VectorXd derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& w) const override {
    return plant_.derivative(x, u, w);
  }
  Eigen::VectorXd output(const Eigen::VectorXd& x) const override {
    Eigen::VectorXd y = plant_.output(x);
    y(0) *= gain_;
    return y;
  }
  void output_into(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override {
    plant_.output_into(x, y);
    y(0) *= gain_;
  }
  void advance(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w, double sample_time,
               int substeps) const override {
    plant_.advance(x, u, w, sample_time, substeps);
  }
  Eigen::VectorXd equilibrium_state() const override { return state_; }
  Eigen::VectorXd equilibrium_input() const override { return input_; }

  void set_operating_point(Eigen::VectorXd state, Eigen::VectorXd input) {
    state_ = std::move(state);
    input_ = std::move(input);
  }
  const sim::Amb1dofVoltage& plant() const { return plant_; }

 private:
  sim::Amb1dofVoltage plant_;
  double gain_;
  Eigen::VectorXd state_, input_;
};

constexpr const char* kAmb1dofFamily = "amb1dof_voltage";

// The monitored parameters of amb1dof_voltage, in their order, and the role of each (the one
// list of them): the identified physical quantities that stand for a fault of their own; the
// others the identifier gives (kr1_emf, kr2_emf) are not watched.
constexpr MonitoredParameter kAmb1dofRoles[] = {
    {"R1", {"coil_resistance", 1, "coil 1 resistance"}},     {"R2", {"coil_resistance", 2, "coil 2 resistance"}},
    {"kw1", {"amplifier_gain", 1, "amplifier 1 gain"}},      {"kw2", {"amplifier_gain", 2, "amplifier 2 gain"}},
    {"kr1", {"force_factor", 1, "coil 1 force factor"}},     {"kr2", {"force_factor", 2, "coil 2 force factor"}},
    {"ks", {"air_gap", std::nullopt, "negative stiffness"}},
};

sim::Amb1dofParameters nominal_of(const Experiment& header) {
  if (header.plant.model != kAmb1dofFamily)  // this file is the amb1dof_voltage family's
    throw Error("fault signatures: plant model '" + header.plant.model + "' is not " + kAmb1dofFamily +
                " (plant_families.hpp fault_hypotheses takes each family's)");
  if (!header.controller) throw Error("fault signatures: the experiment records no controller to close the loop with");
  return sim::Amb1dofParameters::from_map(header.plant.parameters);
}

}  // namespace

std::span<const MonitoredParameter> amb1dof_monitored_parameters() { return kAmb1dofRoles; }

void SignatureOptions::validate() const {
  if (!(relative_step > 0.0 && relative_step < 0.5))
    throw Error("fault signatures: relative_step must be in (0, 0.5), got " + std::to_string(relative_step));
  if (!(settle_tolerance > 0.0) || !std::isfinite(settle_tolerance))
    throw Error("fault signatures: settle_tolerance must be positive, got " + std::to_string(settle_tolerance));
  if (!std::isfinite(settle_time)) throw Error("fault signatures: settle_time is not finite");
}

std::map<std::string, double> settled_parameters(const Experiment& header,
                                                 const std::map<std::string, double>& true_parameters,
                                                 double sensor_gain, const SignatureOptions& options) {
  options.validate();
  const sim::Amb1dofParameters nominal = nominal_of(header);
  if (!(header.sample_time > 0.0) || !(options.settle_time >= 10.0 * header.sample_time))
    throw Error("fault signatures: settle_time " + std::to_string(options.settle_time) +
                " s is shorter than ten samples of " + std::to_string(header.sample_time) + " s");
  if (!(sensor_gain > 0.0) || !std::isfinite(sensor_gain))
    throw Error("fault signatures: sensor gain must be positive, got " + std::to_string(sensor_gain));
  sim::Amb1dofParameters truth = nominal;
  for (const auto& [name, value] : true_parameters) truth.set(name, value);
  truth.validate();
  SensedPlant plant(truth, sensor_gain);

  Experiment loop = header;
  loop.r_names.clear();
  sim::ClosedLoopOptions run;
  run.samples = static_cast<Eigen::Index>(std::llround(options.settle_time / header.sample_time));
  const Experiment settled = sim::run_closed_loop(plant, loop, run);
  const Eigen::Index last = settled.samples() - 1, earlier = last - settled.samples() / 10;
  const Eigen::VectorXd y = settled.y.row(last).transpose(), u = settled.u.row(last).transpose();
  const Eigen::VectorXd u0 = sim::Amb1dofVoltage(nominal).equilibrium_input();
  const Eigen::Vector3d y_scale(nominal.x0, nominal.i0, nominal.i0);
  for (Eigen::Index j = 0; j < 3; ++j)
    if (std::abs(settled.y(last, j) - settled.y(earlier, j)) > options.settle_tolerance * y_scale(j))
      throw Error("fault signatures: " + settled.y_names[static_cast<std::size_t>(j)] + " still moves after " +
                  std::to_string(options.settle_time) + " s of closed loop (the loop does not settle)");
  for (Eigen::Index j = 0; j < 2; ++j)
    if (std::abs(settled.u(last, j) - settled.u(earlier, j)) > options.settle_tolerance * u0(j))
      throw Error("fault signatures: " + settled.u_names[static_cast<std::size_t>(j)] + " still moves after " +
                  std::to_string(options.settle_time) + " s of closed loop (the loop does not settle)");

  // At rest x' = 0; x is what the sensor reads divided by its gain.
  plant.set_operating_point(Eigen::Vector4d(y(0) / sensor_gain, 0.0, y(1), y(2)), u);
  sim::LinearizeOptions lin;
  lin.state_scale = plant.plant().state_scale();
  lin.input_scale = plant.plant().input_scale();
  const ContinuousSystem sys = ident::amb1dof_physical_coordinates(sim::linearize(plant, lin));
  const auto physical = sim::amb1dof_physical_from_structure(sim::amb1dof_structure_parameters(sys), nominal).to_map();
  std::map<std::string, double> out;
  for (const MonitoredParameter& p : kAmb1dofRoles)
    out[std::string(p.parameter)] = physical.at(std::string(p.parameter));
  return out;
}

std::vector<FaultHypothesis> closed_loop_fault_hypotheses(const Experiment& header, const SignatureOptions& options) {
  const sim::Amb1dofParameters nominal = nominal_of(header);
  const std::map<std::string, double> base = settled_parameters(header, {}, 1.0, options);
  const double h = options.relative_step;
  // d log(identified p) / d log(fault parameter), by central differences.
  auto column = [&](const std::string& fault_parameter) {
    std::map<std::string, double> plus, minus;
    double gain_plus = 1.0, gain_minus = 1.0;
    if (fault_parameter == "sensor_gain") {
      gain_plus = 1.0 + h;
      gain_minus = 1.0 - h;
    } else {
      const double v = nominal.get(fault_parameter);
      plus[fault_parameter] = v * (1.0 + h);
      minus[fault_parameter] = v * (1.0 - h);
    }
    const auto up = settled_parameters(header, plus, gain_plus, options);
    const auto down = settled_parameters(header, minus, gain_minus, options);
    std::map<std::string, double> s;
    for (const auto& [name, value] : base) s[name] = (up.at(name) - down.at(name)) / (2.0 * h * value);
    return s;
  };
  auto sum = [](std::map<std::string, double> a, const std::map<std::string, double>& b) {
    for (auto& [name, value] : a) value += b.at(name);
    return a;
  };
  const auto R1 = column("R1"), R2 = column("R2"), kw1 = column("kw1"), kw2 = column("kw2");
  return {
      {"coil_resistance", 1, "coil 1 resistance", {"R1"}, R1},
      {"coil_resistance", 2, "coil 2 resistance", {"R2"}, R2},
      {"coil_resistance", std::nullopt, "resistance of both coils (R1, R2 alike)", {"R1", "R2"}, sum(R1, R2)},
      {"amplifier_gain", 1, "amplifier 1 gain", {"kw1"}, kw1},
      {"amplifier_gain", 2, "amplifier 2 gain", {"kw2"}, kw2},
      {"amplifier_gain", std::nullopt, "gain of both amplifiers (kw1, kw2 alike)", {"kw1", "kw2"}, sum(kw1, kw2)},
      {"force_factor", 1, "coil 1 force factor", {"kr1"}, column("K1")},
      {"force_factor", 2, "coil 2 force factor", {"kr2"}, column("K2")},
      {"air_gap", std::nullopt, "air gap", {"ks"}, column("x0")},
      {"sensor_gain", std::nullopt, "position sensor gain (kr1, kr2 alike)", {}, column("sensor_gain")},
      {"rotor_mass", std::nullopt, "rotor mass (ks, kr1, kr2 alike)", {}, column("m")},
  };
}

const std::vector<FaultHypothesis>& default_fault_hypotheses() {
  static const std::vector<FaultHypothesis> hypotheses = [] {
    sim::ScenarioOptions o;
    o.excitation = "none";
    return closed_loop_fault_hypotheses(sim::build_scenario(o).header);
  }();
  return hypotheses;
}

}  // namespace ambid::diag
