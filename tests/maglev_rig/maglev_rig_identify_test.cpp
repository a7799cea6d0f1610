// `identify --method greybox` on records of the simulated rig as they come off the board
// (tests/support/maglev_records.hpp: the rig's PID with every clamp, reference steps between
// 13 and 16 mm held 1.5 s, uniform noise w of +-0.5 V on u that is not logged, 5 um of sensor
// noise, 0.01 mm / 0.01 V / 0.01 mA logging; the PID and the r reconstructed from u in the
// sidecar) at the rig's four sample times, 4000 samples each: the physical parameters against
// the truth, and the linearisation at the measured operating point (the first level's means).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/linalg.hpp"
#include "core/model_file.hpp"
#include "identifier/identify_experiment.hpp"
#include "support/maglev_records.hpp"

namespace ambid {
namespace maglev_rig_identify_test {

sim::MaglevParameters truth() {
  sim::MaglevParameters p = sim::MaglevParameters::nominal();
  p.R = 205.0;
  p.L = 0.27;
  p.Km = 1.62e-8;
  p.Ke = 1.62e-8;
  return p;
}

// The truth linearised analytically at the measured point (x0, i0): the positive eigenvalue of
// [0 1 0; n_x g/x0 0 -n_i g/i0; 0 emf -R/L], the force and back-EMF constants closed by gravity
// balance there (emf = n_i Ke / rho i0^(n_i-1) / (x0^n_x L), rho = Km i0^n_i / (m g x0^n_x)).
double true_unstable_pole(const sim::MaglevParameters& p, double x0, double i0) {
  const double rho = p.Km * std::pow(i0, p.n_i) / (p.m * p.g * std::pow(x0, p.n_x));
  const double emf = p.n_i * p.Ke / rho * std::pow(i0, p.n_i - 1) / (std::pow(x0, p.n_x) * p.L);
  Eigen::Matrix3d A;
  A << 0, 1, 0, p.n_x * p.g / x0, 0, -p.n_i * p.g / i0, 0, emf, -p.R / p.L;
  return linalg::eigenvalues(A).real().maxCoeff();
}

Model greybox(const Experiment& e) {
  ident::IdentifyOptions o;
  o.method = "greybox";
  return ident::identify_experiment(e, o);
}

TEST(MaglevRigIdentify, PhysicalParametersAtTheRigsSampleTimes) {
  const sim::MaglevParameters p = truth();
  const auto true_values = p.to_map();
  for (const double Ts : {1.3e-3, 1.5e-3, 3.25e-3, 4e-3}) {
    SCOPED_TRACE(Ts);
    const Experiment e =
        test_support::maglev_record(p, sim::MaglevRig{}, test_support::maglev_run_options(Ts, 4000, 7));
    ASSERT_TRUE(e.controller.has_value());  // the board's PID, attached by the rig loop
    ASSERT_EQ(e.r_names, std::vector<std::string>{"r"});
    const Model m = greybox(e);
    for (const char* name : {"R", "L", "Ke", "Km", "n_i", "n_x"})
      std::printf("Ts %.2f ms %-3s %+7.3f %% (sigma %.3f %%)\n", Ts * 1e3, name,
                  100 * (m.physical.at(name) / true_values.at(name) - 1),
                  100 * m.uncertainty.at(name) / true_values.at(name));
    for (const char* name : {"R", "L", "n_i", "n_x"})
      EXPECT_NEAR(m.physical.at(name) / true_values.at(name), 1.0, 0.01) << name;
    // At the measured operating point: the force's slopes n_x g / x0 and n_i g / i0.
    const double x0 = e.operating_point.at("x"), i0 = e.operating_point.at("i");
    EXPECT_NEAR(m.parameters.at("a") / (p.n_x * p.g / x0), 1.0, 0.01);
    EXPECT_NEAR(m.parameters.at("b") / (p.n_i * p.g / i0), 1.0, 0.01);
    // The force constant at the measured point, Km i0^n_i / x0^n_x (the force that holds the
    // body there), and the unstable pole of the linearisation there (with the back-EMF's
    // coupling, 1 % below sqrt(a): the fit read sqrt(a) until 2026-12-03, 1.0-1.1 % high).
    const auto at_point = [&](double Km, double n_i, double n_x) { return Km * std::pow(i0, n_i) / std::pow(x0, n_x); };
    EXPECT_NEAR(
        at_point(m.physical.at("Km"), m.physical.at("n_i"), m.physical.at("n_x")) / at_point(p.Km, p.n_i, p.n_x), 1.0,
        0.01);
    const double pole = true_unstable_pole(p, x0, i0);
    std::printf("Ts %.2f ms unstable pole %+7.3f %% (sigma %.3f %%)\n", Ts * 1e3,
                100 * (m.physical.at("unstable_pole") / pole - 1), 100 * m.uncertainty.at("unstable_pole") / pole);
    EXPECT_NEAR(m.physical.at("unstable_pole") / pole, 1.0, 0.005);
    EXPECT_LT(m.uncertainty.at("unstable_pole") / pole, 0.005);
    // Km and Ke carry m^n_x: an n_x 0.25 % off moves them 4 %. Each within three of its sigma
    // (which holds the exponents' share); the sigma below 3 % where the record spans six
    // levels (3.25, 4 ms) and below 6 % where it spans three (5.2 s at 1.3 ms).
    for (const char* name : {"Ke", "Km"}) {
      const double sigma = m.uncertainty.at(name) / true_values.at(name);
      EXPECT_NEAR(m.physical.at(name) / true_values.at(name), 1.0, 3 * sigma) << name;
      EXPECT_LT(sigma, Ts > 3e-3 ? 0.03 : 0.06) << name;
    }
    // The back-EMF at the measured point, Ke / x0^n_x here, is what the coil equation carries;
    // these records cannot pin it to 1 % (maglev_greybox.hpp: with the true motion known the
    // information bounds its sigma at 1.0-2.3 %), and the fit says so rather than claiming it.
    const double Ke_at_point = p.Ke * std::pow(i0, p.n_i - 1) / std::pow(x0, p.n_x);
    const double Ke_sigma = m.uncertainty.at("Ke_at_point") / Ke_at_point;
    std::printf("Ts %.2f ms Ke_at_point %+7.3f %% (sigma %.3f %%)\n", Ts * 1e3,
                100 * (m.physical.at("Ke_at_point") / Ke_at_point - 1), 100 * Ke_sigma);
    EXPECT_NEAR(m.physical.at("Ke_at_point") / Ke_at_point, 1.0, 3 * Ke_sigma);
    EXPECT_GT(3 * Ke_sigma, 0.01);
    const auto unresolved = m.extra.json().at("greybox").at("unresolved").get<std::vector<std::string>>();
    const auto listed = [&](const char* name) {
      return std::find(unresolved.begin(), unresolved.end(), name) != unresolved.end();
    };
    EXPECT_TRUE(listed("Ke") && listed("Ke_at_point"));
    for (const char* name : {"R", "L", "n_i", "n_x", "rho", "unstable_pole"}) EXPECT_FALSE(listed(name)) << name;
    bool warned = false;
    for (const auto& w : m.extra.json().at("warnings"))
      warned = warned || w.get<std::string>().find("Ke_at_point +-") != std::string::npos;
    EXPECT_TRUE(warned);
  }
}

// The unstable pole of the linearisation at (x, i) of a law with exponents n_i, n_x whose force
// there is `weight` times m g, back-EMF constant Ke: the positive eigenvalue of
// [0 1 0; n_x g/x w 0 -n_i g/i w; 0 n_i Ke i^(n_i-1)/(x^n_x L) -R/L].
double pole_at(double n_i, double n_x, double weight, double Ke, double R, double L, double x, double i) {
  const double g = 9.81;
  Eigen::Matrix3d A;
  A << 0, 1, 0, n_x * g / x * weight, 0, -n_i * g / i * weight, 0,
      n_i * Ke * std::pow(i, n_i - 1) / (std::pow(x, n_x) * L), -R / L;
  return linalg::eigenvalues(A).real().maxCoeff();
}

// The 13 mm level is where `frf` per level has no fit: the loop's command there (2.6 V) swings
// onto the 0 V clamp in bursts (11-19 clamped samples of its ~345 settled ones over seeds 1-7),
// so that no two clamp-free Welch segments of 128 remain, even placed within the clamp-free
// stretches (0-2). The grey-box fit is of the nonlinear model over all levels and needs no
// exogenous segments: linearised at the 13 mm level's means its unstable pole is the truth's
// linearisation there within 0.1 % (seeds 1-7, 3.25 ms; sigma of the fit's pole ~0.04 %).
TEST(MaglevRigIdentify, GreyboxHoldsTheThirteenMillimetreLevelThatFrfCannotFit) {
  const sim::MaglevParameters p = truth();
  const Experiment e =
      test_support::maglev_record(p, sim::MaglevRig{}, test_support::maglev_run_options(3.25e-3, 3000, 7));
  const Model m = greybox(e);
  // The second reference level (13 mm), its second half: settled.
  const auto per_level = Eigen::Index(std::llround(1.5 / e.sample_time));
  const Eigen::Index begin = per_level + per_level / 2, n = per_level - per_level / 2;
  const double x = e.y.col(0).segment(begin, n).mean(), i = e.y.col(1).segment(begin, n).mean();
  ASSERT_NEAR(x, 0.013, 1e-4);
  const double x0 = e.operating_point.at("x"), i0 = e.operating_point.at("i");
  const auto& v = m.physical;
  const double fitted_weight = v.at("rho") * std::pow(i / i0, v.at("n_i")) * std::pow(x0 / x, v.at("n_x"));
  const double fitted = pole_at(v.at("n_i"), v.at("n_x"), fitted_weight, v.at("Ke"), v.at("R"), v.at("L"), x, i);
  const double true_weight = p.Km * std::pow(i, p.n_i) / (p.m * p.g * std::pow(x, p.n_x));
  const double truth_there = pole_at(p.n_i, p.n_x, true_weight, p.Ke, p.R, p.L, x, i);
  std::printf("13 mm level: unstable pole %.3f (truth %.3f, %+.3f %%)\n", fitted, truth_there,
              100 * (fitted / truth_there - 1));
  EXPECT_NEAR(fitted / truth_there, 1.0, 0.002);
  EXPECT_GT(truth_there / true_unstable_pole(p, x0, i0), 1.02);  // a level of its own: 3 % above 14 mm's
}

}  // namespace maglev_rig_identify_test
}  // namespace ambid
