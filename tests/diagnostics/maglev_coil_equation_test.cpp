// The audit's one-step check of the maglev coil (diagnostics/audit/maglev_coil_equation.hpp):
// the coil's exact step response, and on a rig record with a warm coil (R 235 ohm against the
// sidecar's 210) the resistance and the amplifier gain that fit the same steady current
// (kw' = 210 / 235) told apart sample by sample, where the closed-loop replay cannot.
#include <cmath>

#include <gtest/gtest.h>

#include "diagnostics/audit/maglev_coil_equation.hpp"
#include "maglev_audit_cases.hpp"
#include "plant_sim/maglev_effects.hpp"
#include "plant_sim/maglev_extended.hpp"
#include "support/maglev_records.hpp"

namespace ambid::diag {
namespace maglev_coil_equation_test {

double rms_error(const OneStepPrediction& p) {
  const Eigen::Index n = p.measured.rows() - 1;
  return std::sqrt((p.measured - p.predicted).topRows(n).squaredNorm() / double(n));
}

TEST(MaglevCoilEquation, TheCoilsStepResponseOverOneSample) {
  sim::MaglevParameters p = sim::MaglevParameters::nominal();
  p.R = 210.0;
  p.L = 0.3;
  p.kw = 1.0;
  const sim::MaglevExtended coil(p, {0.014, 0.019, 4.0}, true, {}, 4e-3);
  // i(dt) = exp(-R dt / L) i + (1 - exp(-R dt / L)) kw u / R: exp(-2.8) = 0.0608100626.
  EXPECT_NEAR(coil.coil_current_after(0.019, 4.0, 4e-3), 0.0608100626 * 0.019 + 0.9391899374 * 4.0 / 210.0, 1e-12);
  // A DAC of 0.35 V steps puts out 4.2 V for 4.1 V.
  const sim::MaglevExtended dac(
      p, {0.014, 0.019, 4.0}, true,
      {sim::make_effect(sim::maglev_effect_catalogue(), "actuator_quantisation", {{"step", 0.35}})}, 4e-3);
  EXPECT_NEAR(dac.coil_current_after(0.0, 4.1, 4e-3), 0.9391899374 * 4.2 / 210.0, 1e-12);
}

TEST(MaglevCoilEquation, TellsAWarmCoilFromAnAmplifierGainAtFourMilliseconds) {
  const testing::MaglevCase c = testing::maglev_case("coil_resistance");  // R 235 ohm
  sim::MaglevRunOptions run = test_support::maglev_run_options(4e-3, 1500, 11);
  run.levels = {0.014, 0.0145, 0.015, 0.0155};
  const Experiment e = testing::maglev_case_record(c, run);
  ASSERT_NEAR(e.plant.parameters.at("R"), 210.0, 1e-9);
  const auto& catalogue = sim::maglev_effect_catalogue();
  const double right =
      rms_error(maglev_coil_prediction(e, {sim::make_effect(catalogue, "coil_resistance", {{"dR", 25.0}})}));
  const double gain = rms_error(
      maglev_coil_prediction(e, {sim::make_effect(catalogue, "amplifier_gain", {{"dkw", 210.0 / 235.0 - 1.0}})}));
  const double nominal = rms_error(maglev_coil_prediction(e, {}));
  // The right coil leaves the logged current's noise: 10 uA and the 0.01 mA rounding
  // (sqrt(2) (1e-5^2 + 1e-5^2 / 12)^0.5 = 14.7 uA for the difference of two samples, less a's share).
  EXPECT_LT(right, 2e-5);
  EXPECT_GT(gain, 2.0 * right);       // measured 0.050 against 0.016 mA (seed 11, 3000 samples)
  EXPECT_GT(nominal, 100.0 * right);  // the steady current's 12 % off: about 3 mA
}

}  // namespace maglev_coil_equation_test
}  // namespace ambid::diag
