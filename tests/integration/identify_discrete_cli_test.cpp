// `ambid identify` on a record whose identified discrete model has no continuous-time
// equivalent: a linear plant built with a discrete pole at -0.6 (sample time 0.1 ms), in the
// signals of amb1dof_voltage, excited by white noise. The ERA methods find that pole (1e-6
// sensor noise), d2c_zoh refuses it, and model.json keeps the discrete model (checked against
// the plant's eigenvalues and Markov parameters, which no change of coordinates alters), says
// why there is no continuous part, and the command says so on stderr and exits 0.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <complex>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "core/experiment_io.hpp"
#include "core/linalg.hpp"
#include "core/model_file.hpp"
#include "core/state_space.hpp"

namespace ambid {
namespace identify_discrete_cli_test {

using cli_test::CommandResult;
using cli_test::fresh_dir;
using cli_test::read_json;
using cli_test::run_ambid;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

// Eigenvalues 0.95, -0.6, 0.7 +- 0.2i in the coordinates V; outputs x, i1, i2 as the states
// 1, 3, 4 (the output map of amb1dof_voltage's physical coordinates).
DiscreteSystem plant_with_a_negative_real_pole() {
  Eigen::Matrix4d lambda;
  lambda << 0.95, 0, 0, 0, 0, -0.6, 0, 0, 0, 0, 0.7, 0.2, 0, 0, -0.2, 0.7;
  Eigen::Matrix4d v;
  v << 1, 0.2, 0.1, 0, 0.1, 1, 0, 0.3, 0, 0.2, 1, 0.1, 0.3, 0, 0.1, 1;
  Eigen::MatrixXd b(4, 2), c = Eigen::MatrixXd::Zero(3, 4);
  b << 0.5, 0.1, 0.2, 0.4, 1.0, 0.0, 0.0, 1.0;
  c(0, 0) = c(1, 2) = c(2, 3) = 1.0;
  return {v * lambda * linalg::inverse(v), b, c, Eigen::MatrixXd::Zero(3, 2), 1e-4};
}

std::vector<std::complex<double>> sorted_poles(const DiscreteSystem& s) {
  const Eigen::VectorXcd p = poles(s);
  std::vector<std::complex<double>> out(p.data(), p.data() + p.size());
  std::sort(out.begin(), out.end(),
            [](auto a, auto b) { return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag(); });
  return out;
}

// The sidecar of an `ambid sim` run (amb1dof_voltage, its nominal parameters and operating
// point) with 4000 samples of the plant above driven by white noise r (u = r: the recorded
// controller has zero gain).
fs::path write_record(const fs::path& dir, const DiscreteSystem& plant) {
  const fs::path sim = dir / "sim";
  const CommandResult r = run_ambid("sim --duration 0.01 --out " + sim.string());
  EXPECT_EQ(r.status, 0) << r.output;
  Experiment e = read_experiment(sim.string() + ".json").experiment;
  const Eigen::Index n = 4000;
  StateSpaceController k;
  k.sample_time = e.sample_time;
  k.inputs = {"x", "i1", "i2"};
  k.outputs = {"u1", "u2"};
  k.A = Eigen::MatrixXd::Zero(1, 1);
  k.B = Eigen::MatrixXd::Zero(1, 3);
  k.C = Eigen::MatrixXd::Zero(2, 1);
  k.D = Eigen::MatrixXd::Zero(2, 3);
  e.controller = k;
  std::mt19937_64 random(11);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd r_dev(n, 2);
  for (Eigen::Index i = 0; i < r_dev.size(); ++i) r_dev.data()[i] = normal(random);
  // Sensor noise of 1e-6 (outputs of order 1): noise-free, the ARX regressors of a 4-state
  // plant with 3 outputs are exactly rank deficient.
  Eigen::MatrixXd y_dev = simulate(plant, r_dev);
  for (Eigen::Index i = 0; i < y_dev.size(); ++i) y_dev.data()[i] += 1e-6 * normal(random);
  e.t = Eigen::VectorXd::LinSpaced(n, 0.0, double(n - 1) * e.sample_time);
  e.y = y_dev.rowwise() + e.operating_values(e.y_names).transpose();
  e.u = r_dev.rowwise() + e.operating_values(e.u_names).transpose();
  e.r = r_dev.rowwise() + e.operating_values(e.r_names).transpose();
  const fs::path stem = dir / "negative_pole";
  write_experiment(e, stem);
  return stem;
}

TEST(IdentifyCli, ModelWithoutAContinuousEquivalentKeepsTheDiscreteModel) {
  const fs::path dir = fresh_dir("identify_discrete_only");
  const DiscreteSystem truth = plant_with_a_negative_real_pole();
  const std::vector<std::complex<double>> truth_poles = sorted_poles(truth);
  ASSERT_NEAR(truth_poles[0].real(), -0.6, 1e-12);
  ASSERT_EQ(truth_poles[0].imag(), 0.0);
  const fs::path stem = write_record(dir, truth);
  for (const std::string method : {"closed-loop", "okid"}) {
    SCOPED_TRACE(method);
    const fs::path out = dir / (method + ".json");
    const CommandResult r = run_ambid("identify " + stem.string() + " --method " + method + " --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_THAT(r.output, HasSubstr("discrete model only"));
    EXPECT_THAT(r.output, HasSubstr("warning: no continuous-time model (d2c: discrete eigenvalue -0.6"));
    const nlohmann::json j = read_json(out);
    EXPECT_FALSE(j.contains("continuous"));
    EXPECT_THAT(j["no_continuous"].get<std::string>(), HasSubstr("closed negative real axis"));
    const Model m = read_model(out);
    EXPECT_FALSE(m.continuous.has_value());
    EXPECT_TRUE(m.parameters.empty());
    EXPECT_TRUE(m.physical.empty());
    ASSERT_EQ(m.discrete.states(), 4);
    // The poles, and the Markov parameters C A^k B (the same in any coordinates), of the truth.
    const std::vector<std::complex<double>> p = sorted_poles(m.discrete);
    for (std::size_t i = 0; i < p.size(); ++i) EXPECT_LT(std::abs(p[i] - truth_poles[i]), 1e-6) << i;
    EXPECT_LT(m.discrete.D.cwiseAbs().maxCoeff(), 1e-8);
    Eigen::MatrixXd a_k = Eigen::MatrixXd::Identity(4, 4), a_k_truth = a_k;
    for (int k = 0; k < 10; ++k) {
      const Eigen::MatrixXd markov = m.discrete.C * a_k * m.discrete.B, markov_truth = truth.C * a_k_truth * truth.B;
      EXPECT_LT((markov - markov_truth).cwiseAbs().maxCoeff(), 1e-6 * markov_truth.cwiseAbs().maxCoeff()) << k;
      a_k = m.discrete.A * a_k;
      a_k_truth = truth.A * a_k_truth;
    }
    // Validated on the last 25 % as any model: the discrete model reproduces the record.
    for (const char* y : {"x", "i1", "i2"}) EXPECT_LT(m.fit_nrmse.at(y), 1e-4) << y;
  }
}

}  // namespace identify_discrete_cli_test
}  // namespace ambid
