// Ready-made bearing simulations: controllers designed on the nominal model keep the true
// (nonlinear) bearing stable when a coil resistance or an amplifier gain is 20 % off.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/observer_controller.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::sim {
namespace scenario_test {

using ::testing::HasSubstr;

struct Case {
  std::string controller;
  std::string parameter;  // empty: nominal
  double factor;
};

std::vector<Case> cases() {
  std::vector<Case> all;
  for (const std::string c : {"lqr", "pid", "leadlag"}) {
    all.push_back({c, "", 1.0});
    for (const std::string p : {"R1", "R2", "kw1", "kw2"})
      for (double f : {0.8, 1.2}) all.push_back({c, p, f});
  }
  return all;
}

class FaultyBearing : public ::testing::TestWithParam<Case> {};

TEST_P(FaultyBearing, StaysStableAndLevitated) {
  const Case& c = GetParam();
  ScenarioOptions o;
  o.controller = c.controller;
  o.duration = 0.3;
  o.amplitude = 0.05;
  o.seed = 3;
  Amb1dofParameters truth = Amb1dofParameters::nominal();
  if (!c.parameter.empty()) {
    o.true_parameters[c.parameter] = truth.get(c.parameter) * c.factor;
    truth.set(c.parameter, truth.get(c.parameter) * c.factor);
  }
  const Scenario s = build_scenario(o);

  // Linear check: the truth's linearisation with the nominal design.
  const Amb1dofVoltage true_plant(truth);
  const DiscreteSystem cl = linear_closed_loop(c2d_zoh(true_plant.linearize(), o.sample_time), s.header.u_names,
                                               s.header.y_names, *s.header.controller);
  EXPECT_LT(spectral_radius(cl), 0.9995);

  // Nonlinear check: the rotor stays near the centre, far from the 0.35 mm gap.
  const Experiment e = run_closed_loop(*s.truth, s.header, s.options);
  ASSERT_TRUE(e.y.allFinite());
  const double late_peak = e.y.col(0).tail(e.samples() / 2).cwiseAbs().maxCoeff();
  EXPECT_LT(late_peak, 0.05 * truth.x0);
}

INSTANTIATE_TEST_SUITE_P(NominalAndTwentyPercentFaults, FaultyBearing, ::testing::ValuesIn(cases()),
                         [](const auto& test_info) {
                           const Case& c = test_info.param;
                           std::string name = c.controller + "_" + (c.parameter.empty() ? "nominal" : c.parameter);
                           if (!c.parameter.empty()) name += c.factor > 1 ? "_plus20" : "_minus20";
                           return name;
                         });

TEST(Scenario, SidecarKeepsNominalParametersAndRecordsTruth) {
  ScenarioOptions o;
  o.duration = 0.01;
  o.true_parameters["R1"] = 21.0;
  const Scenario s = build_scenario(o);
  EXPECT_DOUBLE_EQ(s.header.plant.parameters.at("R1"), 17.5);
  EXPECT_DOUBLE_EQ(s.header.extra.json()["simulation"]["true_parameters"]["R1"].get<double>(), 21.0);
  EXPECT_DOUBLE_EQ(s.header.operating_point.at("u1"), 8.75);
  EXPECT_EQ(s.header.extra.json()["excitation"]["kind"], "prbs");
}

TEST(Scenario, BadOptionsAreNamed) {
  ScenarioOptions o;
  o.true_parameters["R3"] = 1.0;
  EXPECT_THAT([&] { build_scenario(o); }, ::testing::ThrowsMessage<Error>(HasSubstr("R3")));
  o.true_parameters.clear();
  o.controller = "fuzzy";
  EXPECT_THAT([&] { build_scenario(o); }, ::testing::ThrowsMessage<Error>(HasSubstr("unknown controller 'fuzzy'")));
  o.controller = "lqr";
  o.excitation = "sawtooth";
  EXPECT_THAT([&] { build_scenario(o); }, ::testing::ThrowsMessage<Error>(HasSubstr("unknown excitation 'sawtooth'")));
  o.excitation = "prbs";
  o.duration = -1;
  EXPECT_THAT([&] { build_scenario(o); }, ::testing::ThrowsMessage<Error>(HasSubstr("duration")));
  o.duration = 1;
  o.position_noise = -1e-6;
  EXPECT_THAT([&] { build_scenario(o); }, ::testing::ThrowsMessage<Error>(HasSubstr("position noise")));
}

}  // namespace scenario_test
}  // namespace ambid::sim
