// Seed 000 examples II and III on the NONLINEAR amb1dof_voltage closed loop (plant_sim runner,
// observer/LQR/integral controller designed on the nominal model): coil 1 resistance +20 %
// (example II) and amplifier 1 gain +20 % (example III), identified from the recorded
// experiment by identify_experiment.
//
// Truth (amb1dof_truth.hpp): seed 000 eq. (4) where the loop settles. v5 = R1/L1 and
// v8 = kw1/L1 do not depend on the operating point and must move by exactly +20 % against the
// nominal; v1..v4, v6 scale with i_eq and are compared with the model at i_eq.
// The first 0.1 s (the settling from the nominal to the true operating point) is dropped.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "amb1dof_truth.hpp"
#include "identifier/identify_experiment.hpp"
#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/amb1dof_physical.hpp"
#include "plant_sim/scenario.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace seed000_examples_test {

struct Example {
  std::string parameter;  // changed by +20 %
  std::string v;          // the structure parameter that must move by +20 %
};

void check_example(const Example& example, const std::string& method, double change_tolerance, double rest_tolerance) {
  SCOPED_TRACE(example.parameter + " by " + method);
  const auto nominal = sim::amb1dof_structure_parameters(sim::Amb1dofParameters::nominal());
  sim::ScenarioOptions scenario;
  scenario.duration = 1.1;
  scenario.amplitude = 0.05;
  scenario.true_parameters[example.parameter] = 1.2 * sim::Amb1dofParameters::nominal().to_map().at(example.parameter);
  const auto truth = testing::true_structure(scenario);
  IdentifyOptions o;
  o.method = method;
  o.skip_samples = 1000;
  const Model m = identify_experiment(sim::simulate_scenario(scenario), o);
  const double change = m.parameters.at(example.v) / nominal.at(example.v) - 1.0;
  ::testing::Test::RecordProperty(example.parameter + "_" + method + "_" + example.v + "_change", testing::sci(change));
  EXPECT_NEAR(change, 0.2, change_tolerance);
  // Validated in closed loop on the last 25 %, with the operating-point shift fitted.
  ::testing::Test::RecordProperty(example.parameter + "_" + method + "_nrmse_x", testing::sci(m.fit_nrmse.at("x")));
  EXPECT_LT(m.fit_nrmse.at("x"), 0.01);
  EXPECT_LT(m.fit_nrmse.at("i1"), 0.01);
  for (const auto& [name, value] : truth) {
    const double error = m.parameters.at(name) / value - 1.0;
    ::testing::Test::RecordProperty(example.parameter + "_" + method + "_" + name + "_error", testing::sci(error));
    EXPECT_NEAR(error, 0.0, name == example.v ? change_tolerance / 1.2 : rest_tolerance) << name;
  }
}

TEST(Seed000Examples, CoilResistanceChangeOnTheNonlinearLoop) {
  check_example({"R1", "v5"}, "closed-loop", 0.002, 1e-3);  // measured: +20.00 %, rest <= 1.9e-4
}

TEST(Seed000Examples, AmplifierGainChangeOnTheNonlinearLoop) {
  check_example({"kw1", "v8"}, "closed-loop", 0.002, 1e-3);  // measured: +20.00 %, rest <= 1.9e-4
}

}  // namespace seed000_examples_test
}  // namespace ambid::ident
