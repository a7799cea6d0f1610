// How many RK4 sub-steps per sample the closed-loop runner needs: the default scenario
// (amb1dof_voltage, LQR observer controller, PRBS excitation, 10 kHz) against a reference with
// 64 sub-steps, over 0.2 s. At one sub-step the recorded signals are off by ~1e-7 of their
// excursions (x moves ~60 nm, the currents ~0.26 mA, u ~0.14 V): ~5e-15 m and ~1e-11 A,
// about 1e-7 of the sensor noise of the noisy benchmark scenario (0.1 um, 0.1 mA), so far
// below anything an identification could resolve.
#include <gtest/gtest.h>

#include "plant_sim/integrator.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::sim {
namespace closed_loop_accuracy_test {

Experiment run(int substeps) {
  ScenarioOptions o;
  o.duration = 0.2;
  Scenario s = build_scenario(o);
  s.options.substeps = substeps;
  return run_closed_loop(*s.truth, s.header, s.options);
}

// Largest error over the run, per signal relative to that signal's largest excursion from
// its first sample (the operating point).
double relative_error(const Eigen::MatrixXd& signals, const Eigen::MatrixXd& reference) {
  double e = 0.0;
  for (Eigen::Index j = 0; j < reference.cols(); ++j) {
    const Eigen::ArrayXd excursion = reference.col(j).array() - reference(0, j);
    e = std::max(e, (signals.col(j) - reference.col(j)).cwiseAbs().maxCoeff() / excursion.abs().maxCoeff());
  }
  return e;
}

TEST(ClosedLoopAccuracy, DefaultSubstepsFarBelowIdentificationResolution) {
  const Experiment reference = run(64);
  std::vector<double> errors;
  for (const int substeps : {1, 2, 4}) {
    const Experiment e = run(substeps);
    errors.push_back(std::max(relative_error(e.y, reference.y), relative_error(e.u, reference.u)));
    std::cout << "substeps " << substeps << ": relative error of y and u " << errors.back() << "\n";
  }
  // Fourth order in the step: halving it shrinks the error about 16-fold.
  EXPECT_GT(errors[0] / errors[1], 10.0);
  EXPECT_GT(errors[1] / errors[2], 10.0);
  const Experiment at_default = run(kDefaultSubsteps);
  EXPECT_LT(std::max(relative_error(at_default.y, reference.y), relative_error(at_default.u, reference.u)), 1e-6)
      << "kDefaultSubsteps = " << kDefaultSubsteps;
  // Absolute error against the sensor noise (x 1e-7 m; i1, i2 1e-4 A).
  const Eigen::RowVectorXd error = (at_default.y - reference.y).cwiseAbs().colwise().maxCoeff();
  EXPECT_LT(error(0), 1e-6 * 1e-7);
  EXPECT_LT(error(1), 1e-6 * 1e-4);
  EXPECT_LT(error(2), 1e-6 * 1e-4);
}

}  // namespace closed_loop_accuracy_test
}  // namespace ambid::sim
