// The identifier daemon's pem windows warm-started from the previous window's fit, on windows
// cut from simulated streams of the deployed bearing (0.1 um / 1 mA, 1 V PRBS), against the
// simulation's true coil resistance.
#include "services/daemons/warm_windows.hpp"

#include <gtest/gtest.h>

#include "plant_sim/scenario.hpp"
#include "services/convert/plant_samples.hpp"

namespace ambid::daemons {
namespace {

const bus::Estimate& warm_physical(const bus::IdentifiedModel& m, const std::string& name) {
  for (const auto& e : m.physical)
    if (e.name == name) return e;
  throw std::runtime_error(name + " missing");
}

// The 0.5 s window after 0.25 s of settling of a 0.75 s record, cut from its batches as the daemon does.
Experiment settled_window(double r1, std::uint64_t seed) {
  sim::ScenarioOptions o;
  o.duration = 0.75;
  o.amplitude = 1.0;
  o.position_noise = 1e-7;
  o.current_noise = 1e-3;
  o.seed = seed;
  o.true_parameters = {{"R1", r1}};
  const Experiment record = sim::simulate_scenario(o);
  convert::SampleWindow window(sim::build_scenario(o).header, 5000, 2500);
  for (std::uint64_t seq = 0; seq < 15; ++seq)
    EXPECT_NE(window.add(convert::sample_batch(record, Eigen::Index(seq) * 500, 500, "p", seq, 0.0)).outcome,
              convert::SampleWindow::Outcome::rejected);
  EXPECT_TRUE(window.full());
  return window.take();
}

// A nominal window, then one of the same bearing with coil 1 20 % hot under the same
// description (the sidecar stays nominal): the second starts from the first's fit and still
// reads R1 within 3 of its sigmas of the truth (a warm start must not hold a step back), and
// a window of another description starts cold.
TEST(WarmWindows, PemFollowsAStepOfR1FromThePreviousWindowsFit) {
  WarmWindows windows(ident::window_identify_options("pem"));
  const bus::IdentifiedModel nominal = windows.identify(settled_window(17.5, 11), "d1", "p", 0);
  EXPECT_EQ(windows.warm_fits(), 0u);
  const bus::Estimate& r1 = warm_physical(nominal, "R1");
  EXPECT_NEAR(r1.value, 17.5, 3 * r1.sigma);
  EXPECT_LT(r1.sigma, 0.02 * 17.5);  // tight enough that the step below is 10 sigmas

  const bus::IdentifiedModel hot = windows.identify(settled_window(21.0, 12), "d1", "p", 1);
  EXPECT_EQ(windows.warm_fits(), 1u);
  const bus::Estimate& hot_r1 = warm_physical(hot, "R1");
  EXPECT_NEAR(hot_r1.value, 21.0, 3 * hot_r1.sigma);

  windows.identify(settled_window(17.5, 13), "d2", "p", 2);
  EXPECT_EQ(windows.warm_fits(), 1u);
}

}  // namespace
}  // namespace ambid::daemons
