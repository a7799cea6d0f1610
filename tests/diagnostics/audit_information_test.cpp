// How much a record of the confusion table (audit_independent_cases.hpp) can say about one coil's
// leakage inductance Ls_j, whatever the test: the Fisher information of the relative error
// e = Ls_j / Ls_j,nominal - 1 in the validation half, from the replay's sensitivity dy/de
// (central difference of the closed-loop replay, diagnostics/audit/audit_replay.hpp) and the
// noise of the record itself (the residual of the true model, whitened by its joint
// autoregression, audit_whitening.hpp: innovations independent over time and outputs), and its
// Cramer-Rao bound sd(e) >= 1 / sqrt(I). The audit's tests run at z 2.88 (Bonferroni over five
// candidates at 1 %), so an unbiased test finds e 90 % of the time from (2.88 + 1.28) sd(e) at
// best. The drawn errors (5-10 %) stay below that: coil_inductance is "none" in the confusion
// table because the record does not hold it at 0.1 um / 1 mA, not because a test is weak.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "audit_independent_cases.hpp"
#include "diagnostics/audit/audit_replay.hpp"
#include "diagnostics/audit/audit_whitening.hpp"

namespace ambid::diag {
namespace audit_information_test {

Eigen::MatrixXd replay_with_inductance(const Experiment& measured, int channel, double relative) {
  Experiment header = measured;
  header.plant.parameters.at("Ls" + std::to_string(channel)) *= 1.0 + relative;
  return replay_outputs(header, {}, measured.samples());
}

// Fisher information about e (relative error of Ls_channel) in `segment`, noise from `truth_y`.
double inductance_information(const Experiment& measured, int channel, const Eigen::MatrixXd& truth_y,
                              const Segment& segment) {
  constexpr double kStep = 0.02;
  const Eigen::MatrixXd S =
      (replay_with_inductance(measured, channel, kStep) - replay_with_inductance(measured, channel, -kStep)) /
      (2.0 * kStep);
  const Eigen::MatrixXd noise = measured.y_deviation() - truth_y;
  const NoiseWhitening w = fit_noise_whitening(noise, segment);
  const Eigen::MatrixXd white_noise = w.apply(noise).middleRows(segment.begin, segment.size());
  const Eigen::MatrixXd white_S = w.apply(S).middleRows(segment.begin, segment.size());
  double information = 0.0;
  for (Eigen::Index j = 0; j < S.cols(); ++j)
    information += white_S.col(j).squaredNorm() / (white_noise.col(j).squaredNorm() / double(segment.size()));
  return information;
}

TEST(AuditInformation, CoilInductanceErrorsOfTheConfusionTableAreBelowTheRecordsInformation) {
  const double z_test = 2.88 + 1.28;  // the audit's threshold plus the 90 % power margin
  for (std::uint64_t s = 0; s < 3; ++s) {
    std::string what;
    // The draws of AuditIndependentSlow.ConfusionTable's coil_inductance row.
    const test_support::EffectRecordOptions o = testing::out_of_catalogue_record("coil_inductance", 32000 + s, s, what);
    const Experiment measured = test_support::simulate_effect_record(o);
    const int channel = o.out_of_catalogue.inductance_channel;
    const double truth = o.out_of_catalogue.inductance_error;
    const Eigen::Index N = measured.samples();
    const Segment validation{N / 2, N, {}};
    const Eigen::MatrixXd truth_y = replay_with_inductance(measured, channel, truth);
    const double sd = 1.0 / std::sqrt(inductance_information(measured, channel, truth_y, validation));
    const double sd_record = 1.0 / std::sqrt(inductance_information(measured, channel, truth_y, {0, N, {}}));
    std::cerr << o.controller << " " << what << ": Cramer-Rao sd(e) " << sd << " on the validation half (" << sd_record
              << " on the whole record); expected z " << std::abs(truth) / sd << "; found 90 % of the time from |e| "
              << z_test * sd << "\n";
    EXPECT_GT(sd, 0.0);
    EXPECT_LT(std::abs(truth) / sd, 2.88) << what << ": the record holds this error above the audit's threshold";
  }
}

}  // namespace audit_information_test
}  // namespace ambid::diag
