#pragma once
// The true v1..v9 of a simulated amb1dof_voltage scenario: the loop integrates x only, so with
// a changed coil or amplifier it settles at another operating point (both bias currents drop
// to the same i_eq, measured here from an unexcited run of the same loop); the true linear
// model is seed 000 eq. (4) of the true parameters at x = 0, i1 = i2 = i_eq.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/amb1dof_physical.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::ident::testing {

inline std::map<std::string, double> true_structure(const sim::ScenarioOptions& scenario) {
  sim::ScenarioOptions rest = scenario;
  rest.excitation = "none";
  rest.position_noise = rest.current_noise = rest.force_noise = 0.0;
  const Experiment e = sim::simulate_scenario(rest);
  const Eigen::RowVectorXd last = e.y.bottomRows(1);
  EXPECT_LT(std::abs(last(0)), 1e-12);                     // x back at 0 (integral action)
  EXPECT_LT(std::abs(last(1) - last(2)), 1e-9 * last(1));  // equal currents (K1 = K2)
  sim::Amb1dofParameters truth = sim::Amb1dofParameters::nominal();
  for (const auto& [name, value] : scenario.true_parameters) truth.set(name, value);
  truth.i0 = last(1);
  return sim::amb1dof_structure_parameters(truth);
}

}  // namespace ambid::ident::testing
