// The residual check with null replicas (audit_residual_check.hpp, "noise that r itself
// carries"): an excitation reconstructed from a rounded record holds the controller's answer to
// the rounding, r = w - kd (q[k] - q[k-1]), and a right model's residual holds q itself. Without
// the replicas the check rejects such a residual every time; with replicas of the same mechanism
// (other q, the same w) it rejects at its stated rate, and still rejects a residual that holds r
// through a wrong model.
#include <functional>
#include <random>
#include <utility>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "diagnostics/audit/audit_residual_check.hpp"

namespace ambid::diag {
namespace audit_residual_check_replicas_test {

constexpr Eigen::Index kSamples = 1500;  // the validation half of a 3000-sample rig record
constexpr double kStep = 1e-5;           // the logger's 0.01 mm
constexpr double kGain = 3.0e4;          // V/m: the rig's derivative gain at 3.25 ms (30.8 V/mm)

// The rounding q of one record (uniform within half a step) and what it does to r and to the
// residual of the right model (q plus 2 um of sensor noise).
NullReplica rounded_record(const Eigen::VectorXd& w, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> rounding(-0.5 * kStep, 0.5 * kStep);
  std::normal_distribution<double> sensor(0.0, 2e-6);
  Eigen::VectorXd q(kSamples);
  for (Eigen::Index k = 0; k < kSamples; ++k) q(k) = rounding(rng);
  NullReplica out{Eigen::MatrixXd(kSamples, 1), Eigen::MatrixXd(kSamples, 1)};
  for (Eigen::Index k = 0; k < kSamples; ++k) {
    out.excitation(k, 0) = w(k) - kGain * (q(k) - (k > 0 ? q(k - 1) : 0.0));
    out.residual(k, 0) = q(k) + sensor(rng);
  }
  return out;
}

Eigen::VectorXd excitation(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);  // the rig's +-0.5 V
  Eigen::VectorXd w(kSamples);
  for (Eigen::Index k = 0; k < kSamples; ++k) w(k) = uniform(rng);
  return w;
}

// Eight rounded records of the same w, each passed through `transform` (none by default).
template <class Transform = std::identity>
std::vector<NullReplica> replicas_of(const Eigen::VectorXd& w, std::mt19937_64& rng, Transform transform = {}) {
  std::vector<NullReplica> out;
  for (int m = 0; m < 8; ++m) out.push_back(transform(rounded_record(w, rng)));
  return out;
}

TEST(AuditResidualCheckReplicas, TheRoundingsOwnCoherenceIsNotAModelError) {
  std::mt19937_64 rng(2026);
  constexpr int kTrials = 200;
  constexpr double kAlpha = 0.05;
  int rejected_plain = 0, rejected_with_replicas = 0;
  for (int t = 0; t < kTrials; ++t) {
    const Eigen::VectorXd w = excitation(rng);
    const NullReplica record = rounded_record(w, rng);
    rejected_plain += residual_check(record.residual, record.excitation, kAlpha).consistent ? 0 : 1;
    const ResidualCheck c = residual_check(record.residual, record.excitation, kAlpha, {}, replicas_of(w, rng));
    ASSERT_TRUE(c.determinable);
    EXPECT_EQ(c.null_replicas, 8);
    rejected_with_replicas += c.consistent ? 0 : 1;
  }
  EXPECT_GE(rejected_plain, kTrials - 2);  // the rounding alone: coherent with r
  // 10 expected at 5 %; 19 or more happen with probability < 0.5 % if the rate is 5 %.
  EXPECT_LE(rejected_with_replicas, 18);
  EXPECT_GE(rejected_with_replicas, 1);  // not a check that can never reject
}

TEST(AuditResidualCheckReplicas, AResidualDrivenByRStillFailsIt) {
  std::mt19937_64 rng(7);
  const Eigen::VectorXd w = excitation(rng);
  NullReplica record = rounded_record(w, rng);
  // r through a lag of 5 samples, 30 um per volt: a wrong plant, about the rounding's rms.
  double lagged = 0.0;
  for (Eigen::Index k = 0; k < kSamples; ++k) {
    lagged += (record.excitation(k, 0) - lagged) / 5.0;
    record.residual(k, 0) += 3e-5 * lagged;
  }
  const ResidualCheck c = residual_check(record.residual, record.excitation, 0.01, {}, replicas_of(w, rng));
  EXPECT_FALSE(c.consistent) << "p " << c.p_value;
  EXPECT_LT(c.p_value, 1e-4);
}

// A record of the same mechanism whose residual also holds r through a gain that differs from
// record to record (drawn anew for each, mean zero): noise, not a model error, but one that
// moves the whole record's coherence at once, which the law of independent windows does not
// allow for. The replicas' own spread does.
NullReplica with_random_gain(NullReplica record, std::mt19937_64& rng) {
  std::normal_distribution<double> gain(0.0, 1.2e-6);  // m/V, a few percent of the rounding's rms
  const double g = gain(rng);
  for (Eigen::Index k = 0; k < kSamples; ++k) record.residual(k, 0) += g * record.excitation(k, 0);
  return record;
}

TEST(AuditResidualCheckReplicas, TheReplicasSpreadWidensTheNullWhereTheWindowsAreNotIndependent) {
  std::mt19937_64 rng(11);
  constexpr int kTrials = 200;
  constexpr double kAlpha = 0.05;
  int rejected = 0, rejected_one_replica_pair = 0;
  for (int t = 0; t < kTrials; ++t) {
    const Eigen::VectorXd w = excitation(rng);
    const NullReplica record = with_random_gain(rounded_record(w, rng), rng);
    const std::vector<NullReplica> replicas =
        replicas_of(w, rng, [&rng](NullReplica r) { return with_random_gain(std::move(r), rng); });
    rejected += residual_check(record.residual, record.excitation, kAlpha, {}, replicas).consistent ? 0 : 1;
    // Two replicas: too few to measure a spread, the law of independent windows alone.
    const std::vector<NullReplica> two(replicas.begin(), replicas.begin() + 2);
    rejected_one_replica_pair += residual_check(record.residual, record.excitation, kAlpha, {}, two).consistent ? 0 : 1;
  }
  EXPECT_GE(rejected_one_replica_pair, 40);  // 10 expected at 5 % if the windows were independent
  EXPECT_LE(rejected, 18);                   // 19 or more: < 0.5 % if the rate is 5 %
}

TEST(AuditResidualCheckReplicas, AReplicaOfOtherSizeIsAnError) {
  std::mt19937_64 rng(3);
  const Eigen::VectorXd w = excitation(rng);
  const NullReplica record = rounded_record(w, rng);
  NullReplica shorter{record.residual.topRows(kSamples - 1), record.excitation.topRows(kSamples - 1)};
  EXPECT_THROW(residual_check(record.residual, record.excitation, 0.01, {}, {shorter}), Error);
}

}  // namespace audit_residual_check_replicas_test
}  // namespace ambid::diag
