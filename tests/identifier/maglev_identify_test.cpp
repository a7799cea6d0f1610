// identify_experiment on maglev1coil_voltage records: method greybox writes the linearisation at
// the measured operating point and the nominal model's own equilibrium there; family-bound
// methods on another family name the families that offer them.
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "identifier/identify_experiment.hpp"
#include "plant_sim/maglev_loop.hpp"

namespace ambid::ident {
namespace maglev_identify_test {

TEST(MaglevIdentify, GreyboxWritesTheLinearisationAtTheMeasuredPointAndTheNominalEquilibriumGap) {
  sim::MaglevParameters truth = sim::MaglevParameters::nominal();
  truth.Km = truth.Ke = 1.62e-8;  // the nominal model (1.5e-8) holds 14 mm with 8 % more current
  sim::MaglevRunOptions o;
  o.samples = 3000;
  o.step_period = 1.5;
  const Experiment e = sim::run_maglev_rig(truth, sim::MaglevParameters::nominal(), sim::MaglevRig{}, o).experiment;
  IdentifyOptions options;
  options.method = "greybox";
  const Model m = identify_experiment(e, options);
  const double x0 = e.operating_point.at("x"), i0 = e.operating_point.at("i");
  ASSERT_TRUE(m.continuous.has_value());
  EXPECT_NEAR(m.continuous->A(1, 0) / (4.0 * 9.81 / x0), 1.0, 0.01);  // n_x g / x0
  EXPECT_NEAR(m.continuous->A(1, 2) / (-9.81 / i0), 1.0, 0.01);       // -n_i g / i0
  EXPECT_NEAR(m.continuous->A(2, 2) / (-truth.R / truth.L), 1.0, 0.01);
  // The identified plant keeps its unstable pole (nothing stabilises it).
  double largest = -1e300;
  for (const auto& p : linalg::eigenvalues(m.continuous->A)) largest = std::max(largest, p.real());
  EXPECT_GT(largest, 40.0);
  const auto& op = m.extra.json().at("operating_point");
  EXPECT_EQ(op.at("source"), "measured");
  // Independent truth: the nominal law's current at x0, i = m g x0^4 / Km.
  EXPECT_NEAR(op.at("nominal_equilibrium_current").get<double>(), 7.4e-4 * 9.81 * std::pow(x0, 4) / 1.5e-8, 1e-12);
  EXPECT_NEAR(op.at("current_ratio").get<double>(), 1.5 / 1.62, 0.005);  // measured / nominal = Km / Km_true
}

std::string error_of(const Experiment& e, const std::string& method) {
  IdentifyOptions options;
  options.method = method;
  try {
    identify_experiment(e, options);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(MaglevIdentify, FamilyBoundMethodsNameTheFamiliesThatOfferThem) {
  sim::MaglevRunOptions o;
  o.samples = 200;
  Experiment e =
      sim::run_maglev_rig(sim::MaglevParameters::nominal(), sim::MaglevParameters::nominal(), sim::MaglevRig{}, o)
          .experiment;
  EXPECT_EQ(error_of(e, "pem"),
            "identify: method 'pem' is defined for plant model 'amb1dof_voltage' only, got 'maglev1coil_voltage'");
  e.plant.model = "maglev2coil";
  EXPECT_EQ(error_of(e, "greybox"),
            "identify: method 'greybox' is defined for plant model 'maglev1coil_voltage' only, got 'maglev2coil' "
            "(known plant models: amb1dof_voltage, maglev1coil_voltage, lamstf)");
}

}  // namespace maglev_identify_test
}  // namespace ambid::ident
