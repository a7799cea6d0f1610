// The recursive prediction-error method (`rpem`: recursive_identification.hpp,
// families/amb1dof_recursive_pem.hpp) on records it did not generate
// (tests/support/amb1dof_records.hpp: the NONLINEAR bearing, RK4 at 16 steps per sample, three
// controllers), at a real bearing's sensor noise (0.1 um on x, 1 mA on each current), against
// the true plant linearised where its loop settles, and against the batch method (`pem`) on the
// same data: with a growing memory the recursive estimate minimises the same criterion, so the
// batch sigma is the precision it can reach. Also: it tracks a step in R1 with forgetting, its
// sigma matches the scatter over seeds, and the UD update is the covariance update it replaces.
#include "identifier/recursive_identification.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "amb1dof_pem_checks.hpp"
#include "core/error.hpp"
#include "identifier/time_domain/ud_covariance.hpp"
#include "plant_sim/amb1dof_parameters.hpp"

namespace ambid::ident {
namespace amb1dof_recursive_pem_test {

using testing::Amb1dofRecord;
using testing::Amb1dofRecordOptions;

// The settled part of a record (the part the batch method fits too).
Experiment settled_part(const Amb1dofRecord& record) {
  return experiment_segment(record.experiment, record.settled, record.experiment.samples());
}

double relative_error(const Model& m, const std::string& name, const std::map<std::string, double>& truth) {
  return m.parameters.at(name) / truth.at(name) - 1.0;
}

class RecursivePemConverges : public ::testing::TestWithParam<std::string> {};

// 10 s at 0.1 um / 1 mA with a growing memory (forgetting 1), from the nominal model: every
// v1..v9 within 4 batch sigmas of the truth plus the batch method's own error (both estimate
// the same criterion's minimum; the batch sigma is what the data allow), its reported sigma
// within a factor 2 of the batch one, and no update rejected at the end.
TEST_P(RecursivePemConverges, EveryVToTheTruthWithinTheBatchPrecision) {
  Amb1dofRecordOptions o = testing::noisy_record(GetParam(), 10.0, 11);
  o.amplitude = testing::noisy_amplitude(GetParam());
  const Amb1dofRecord record = testing::simulate_amb1dof_record(o);
  const Model batch = testing::identify_pem(record);
  RecursiveIdentification recursive({.forgetting = 1.0});
  recursive.add(settled_part(record));
  const Model m = recursive.estimate().model;
  for (const auto& [name, value] : record.truth) {
    const double error = relative_error(m, name, record.truth), batch_error = relative_error(batch, name, record.truth);
    const double batch_sigma = batch.uncertainty.at(name) / value, sigma = m.uncertainty.at(name) / value;
    ::testing::Test::RecordProperty(GetParam() + "_" + name + "_error", testing::sci(error));
    ::testing::Test::RecordProperty(GetParam() + "_" + name + "_batch_error", testing::sci(batch_error));
    ::testing::Test::RecordProperty(GetParam() + "_" + name + "_sigma", testing::sci(sigma));
    ::testing::Test::RecordProperty(GetParam() + "_" + name + "_batch_sigma", testing::sci(batch_sigma));
    EXPECT_LT(std::abs(error), std::abs(batch_error) + 4.0 * batch_sigma) << name;
    EXPECT_LT(sigma, 2.0 * batch_sigma) << name;
    EXPECT_GT(sigma, batch_sigma / 2.0) << name;
  }
  EXPECT_EQ(m.extra.json()["rpem"]["samples"].get<std::uint64_t>(),
            std::uint64_t(record.experiment.samples() - record.settled));
}

INSTANTIATE_TEST_SUITE_P(Controllers, RecursivePemConverges,
                         ::testing::ValuesIn(testing::amb1dof_record_controllers()));

// Rows [begin, end) of a record as a stretch, its time shifted by `shift` (rpem needs no
// controller state: the direct method uses the recorded plant input).
Experiment stretch(const Experiment& e, Eigen::Index begin, Eigen::Index end, double shift = 0.0) {
  Experiment s = e;
  s.t = e.t.segment(begin, end - begin).array() + shift;
  s.y = e.y.middleRows(begin, end - begin);
  s.u = e.u.middleRows(begin, end - begin);
  if (e.r.size() > 0) s.r = e.r.middleRows(begin, end - begin);
  return s;
}

// R1 +20 % from one sample to the next (LQR loop, 0.1 um / 1 mA, 2 V): 3 s of the nominal
// bearing, then a record of the faulty one from rest at the nominal operating point (its loop
// re-settles to the new bias currents, as after a real fault; the two records are joined with a
// gap, so the predictor restarts from the measurement at rest instead of seeing the jump between
// two simulations). With the defaults (memory 1 s, the offsets' random walk) the estimate of R1
// is within 5 % of the new truth kTrack after the step and stays there; it was within 5 % of
// the nominal R1 before. 5 % is ~2.5 sigma of R1 at this memory (scatter over seeds 1.8 %,
// SigmaMatchesTheScatterOverSeeds), the step 20 %. Measured: tracked 0.1 s after the step (the
// coil rows' offsets tied to the bias current, jump detection; worst error after 1.3 %); with
// free offsets w it took ~4.5-5 s, v5 and w, both driven by the constant current deviation,
// separating only slowly.
TEST(RecursivePem, TracksAStepInR1WithForgetting) {
  constexpr double kTrack = 1.0;  // s
  const Amb1dofRecord before = testing::simulate_amb1dof_record(testing::noisy_record("lqr", 3.0, 21));
  Amb1dofRecordOptions o = testing::noisy_record("lqr", 9.5, 22);
  o.true_parameters["R1"] = 1.2 * sim::Amb1dofParameters::nominal().get("R1");
  const Amb1dofRecord after = testing::simulate_amb1dof_record(o);
  const double nominal = before.true_parameters.get("R1"), faulty = after.true_parameters.get("R1");
  RecursiveIdentification recursive;
  const Experiment& a = before.experiment;
  recursive.add(stretch(a, before.settled, a.samples()));
  const double r1_before = recursive.estimate().model.physical.at("R1");
  ::testing::Test::RecordProperty("R1_error_before", testing::sci(r1_before / nominal - 1.0));
  EXPECT_LT(std::abs(r1_before / nominal - 1.0), 0.05);

  const Experiment& b = after.experiment;
  const double shift = a.t(a.samples() - 1) + 2.0 * a.sample_time - b.t(0);  // one sample missing
  const Eigen::Index step = Eigen::Index(std::llround(0.1 / b.sample_time));
  double tracked_at = -1.0, worst_after = 0.0;
  for (Eigen::Index begin = 0; begin < b.samples(); begin += step) {
    recursive.add(stretch(b, begin, std::min(begin + step, b.samples()), shift));
    const double since = double(std::min(begin + step, b.samples())) * b.sample_time;
    const double error = recursive.estimate().model.physical.at("R1") / faulty - 1.0;
    if (std::abs(error) < 0.05 && tracked_at < 0.0) tracked_at = since;
    if (std::abs(error) >= 0.05) tracked_at = -1.0;  // not yet for good
    if (since >= kTrack) worst_after = std::max(worst_after, std::abs(error));
  }
  ::testing::Test::RecordProperty("R1_tracked_after_s", testing::sci(tracked_at));
  ::testing::Test::RecordProperty("R1_worst_error_after_track", testing::sci(worst_after));
  EXPECT_GT(tracked_at, 0.0);
  EXPECT_LE(tracked_at, kTrack);
  EXPECT_LT(worst_after, 0.05);
  ::testing::Test::RecordProperty("projections", std::to_string(recursive.projections()));
}

// Over 10 seeds (LQR loop, 3 s at 2 V, 0.1 um / 1 mA, defaults): the reported sigma of R1, R2,
// kw1, kw2 and of every v at the end is between half and 2.5 times the scatter of the estimates
// over the seeds (10 seeds give the scatter to ~25 %; the offsets' random walk makes the sigma
// conservative: measured 0.8 (v4, v6) to 2.25 (v3) times the scatter), and their mean within 3
// standard errors plus 0.5 % of the truth. A sigma from P alone without S2 / S1, or without
// Lambda, would be off by far more.
TEST(RecursivePem, SigmaMatchesTheScatterOverSeeds) {
  constexpr int kSeeds = 10;
  std::map<std::string, std::vector<double>> errors, sigmas;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const Amb1dofRecord record = testing::simulate_amb1dof_record(testing::noisy_record("lqr", 3.0, 100 + seed));
    RecursiveIdentification recursive;
    recursive.add(settled_part(record));
    const Model m = recursive.estimate().model;
    for (const auto& [name, value] : record.truth) {
      errors[name].push_back(m.parameters.at(name) / value - 1.0);
      sigmas[name].push_back(m.uncertainty.at(name) / value);
    }
    for (const std::string name : {"R1", "R2", "kw1", "kw2"}) {
      const double truth = record.true_parameters.get(name);
      errors[name].push_back(m.physical.at(name) / truth - 1.0);
      sigmas[name].push_back(m.uncertainty.at(name) / truth);
    }
  }
  for (const auto& [name, e_list] : errors) {
    const Eigen::Map<const Eigen::VectorXd> e(e_list.data(), kSeeds), s(sigmas[name].data(), kSeeds);
    const double mean = e.mean(), scatter = std::sqrt((e.array() - mean).square().sum() / double(kSeeds - 1));
    ::testing::Test::RecordProperty(name + "_scatter", testing::sci(scatter));
    ::testing::Test::RecordProperty(name + "_sigma", testing::sci(s.mean()));
    ::testing::Test::RecordProperty(name + "_mean_error", testing::sci(mean));
    EXPECT_LT(s.mean(), 2.5 * scatter) << name;
    EXPECT_GT(s.mean(), scatter / 2.0) << name;
    EXPECT_LT(std::abs(mean), 3.0 * scatter / std::sqrt(double(kSeeds)) + 0.005) << name;
  }
}

// A record of another plant family, or without the nominal parameters, is refused by name; so
// are per-window calls without per-window estimates and a follow threshold that is not > 0.
TEST(RecursivePem, RefusesWhatItCannotIdentify) {
  const Amb1dofRecord record = testing::simulate_amb1dof_record(testing::noisy_record("lqr", 0.2, 1));
  Experiment other = record.experiment;
  other.plant.model = "maglev1coil_voltage";
  RecursiveIdentification recursive;
  EXPECT_THROW(recursive.estimate(), InsufficientData);
  EXPECT_THROW(recursive.add(other), Error);
  EXPECT_FALSE(recursive.started());
  EXPECT_THROW(RecursiveIdentification({.forgetting = 1.5}), Error);
  EXPECT_THROW(recursive.begin_window(0.1), Error);
  EXPECT_THROW(recursive.end_window(), Error);
  EXPECT_THROW(RecursiveIdentification({.window_estimates = true, .follow_surprise = 0.0}), Error);
}

// Bierman's update of U D U' is the covariance update it replaces: P - P h h' P / (h' P h + r)
// and the gain P h / (h' P h + r), with forgetting P / lambda and random walks P + c a a'
// between, on random data.
TEST(UdCovariance, IsTheCovarianceUpdate) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  const Eigen::Index n = 6;
  Eigen::VectorXd initial(n);
  for (Eigen::Index i = 0; i < n; ++i) initial(i) = std::pow(10.0, double(i) - 3.0);
  UdCovariance ud(initial, 1e6);
  Eigen::MatrixXd P = initial.asDiagonal();
  Eigen::VectorXd h(n), gain(n);
  for (int k = 0; k < 50; ++k) {
    for (Eigen::Index i = 0; i < n; ++i) h(i) = normal(rng);
    const double r = 0.5 + std::abs(normal(rng));
    ud.forget(0.98);
    P /= 0.98;
    if (k % 2 == 0) {
      Eigen::VectorXd a(n);
      for (Eigen::Index i = 0; i < n; ++i) a(i) = normal(rng);
      P += 0.3 * a * a.transpose();
      ud.add(0.3, a);
    }
    ud.update(h, r, gain);
    const Eigen::VectorXd expected_gain = P * h / (h.dot(P * h) + r);
    P -= P * h * h.transpose() * P / (h.dot(P * h) + r);
    EXPECT_LT((gain - expected_gain).norm(), 1e-9 * expected_gain.norm()) << k;
    EXPECT_LT((ud.covariance() - P).norm(), 1e-9 * P.norm()) << k;
    EXPECT_GT(ud.d().minCoeff(), 0.0);
  }
  EXPECT_LT((ud.variances() - P.diagonal()).norm(), 1e-9 * P.diagonal().norm());
  EXPECT_THROW(UdCovariance(Eigen::VectorXd::Zero(3)), Error);
  EXPECT_THROW(ud.forget(1.5), Error);
  // scale(c): P <- c P, every correlation kept (the prior of a window estimate).
  ud.scale(10.0);
  EXPECT_LT((ud.covariance() - 10.0 * P).norm(), 1e-9 * 10.0 * P.norm());
  EXPECT_THROW(ud.scale(0.0), Error);
}

}  // namespace amb1dof_recursive_pem_test
}  // namespace ambid::ident
