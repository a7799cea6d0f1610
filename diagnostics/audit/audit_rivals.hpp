#pragma once
// Which of a round's rival findings the audit takes (issue 17; the rivals: significant
// findings whose residual passes the check, audit.hpp): each is tested head to head against
// every other on the validation segment, and the one the fewest others beat is taken (ties:
// the better score, i.e. the z against the model it extends).
//
// Why not the best z against the base model alone: that z is the evidence against noise of
// each finding's own change d = y_effect - y_base, and it grows where the noise is small, not
// where the finding is right. Two effects that both explain a static shift (a coil resistance
// and an amplifier gain both move the bias currents) reach z in the hundreds on that shift,
// and the one whose change lies more in the slow, quiet part of the spectrum wins even when it
// predicts worse: on an independent PID record with amplifier 2's gain -0.28, coil_resistance2
// scored z 710 against amplifier_gain2's 90, though the amplifier gain's NRMSE was the lower
// (0.801 against 0.819).
//
// The head-to-head test is the improvement test (audit_significance.hpp) with the rival's
// replay as the base, on signals whitened by one joint autoregression of the outputs
// (audit_whitening.hpp: each output predicted from the past of all outputs and from the outputs
// before it at the same sample), fitted (QR) to the validation residual of the best-scored
// rival and applied alike to the measurement and every replay: its z is then the evidence in
// the direction where the two differ, weighted by the noise's own spectrum and with the part
// of each output's noise that the others predict taken out.
//
// Why joint: in closed loop the sensor noise, the process force and the current noise are fed
// around the loop, so the residuals of x, i1 and i2 share most of their noise (the nominal
// NRMSE is 0.5-0.9 from noise alone on the independent records). Two rivals that rescale the
// loop alike (a heavier rotor and a sensor gain: both scale the loop gain by about m/(m+dm)
// above the negative-stiffness corner sqrt(ks/m)/2pi = 140 Hz, and differ only below it, where
// the loop gain is high and the closed loop hides the plant; a sensor delay and an eddy-current
// lag: the same phase at the loop's crossover, they differ by the lag's magnitude
// 1/sqrt(1 + (w tau)^2) at high frequency) differ by little against that noise per output, but
// the noise is predictable from the other outputs, the difference is not. Whitened per output
// alone, the right one of each pair beat the wrong one on the confusion table's draws by z
// -0.4-2.4 (rotor mass / sensor gain: 0.9-1.9 either way; eddy current / sensor delay under
// PID: the wrong one ahead, 2.0 against 1.3); jointly, by z 2.8-4.0 and 5.5-19.9 with the wrong
// one over the right at most 2.5 (tests/diagnostics/audit_confusion_slow_test.cpp). Whitening
// per output already mattered: on the independent records the right one of amplifier gain and
// coil resistance beat the wrong one by z 0.5-4.7 unwhitened, by z 5.5-16 whitened, the wrong
// one the right by at most 1.9. The whitening filter changes the test's power, not its
// validity (the improvement test estimates the remaining noise covariance itself).
//
// A family whose model predicts some output one sample ahead from the record alone
// (maglev1coil_voltage: the coil's current, maglev_coil_equation.hpp) gives the head to head a
// second test: the same improvement test on those one-step predictions (their residual is the
// logged output's own noise for the right model, nearly white: no whitening). Where two rivals
// predict alike there (effects that leave the equation alone) it ties at z near 0; where the
// replay cannot tell them (a coil resistance and an amplifier gain at 4 ms: replay z 0.6 either
// way, one-step current residual 0.016 mA against 0.050 mA rms) it can. A's z over B is the
// larger of the two tests'.
//
// A beats B when z(A over B) > margin and z(A over B) > z(B over A). Under "B is right" the
// first z is near standard normal (measured: up to 2.6 for one channel of a coil resistance
// over the other, where the two differ by little), hence AuditOptions::rival_margin 3.
#include <algorithm>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "diagnostics/audit/audit_replay.hpp"

namespace ambid::diag {

struct RivalChoice {
  std::size_t pick = 0;        // index into the replays
  Eigen::MatrixXd z;           // z(a, b): a's validation improvement over b, replays (diagonal 0)
  Eigen::MatrixXd z_one_step;  // the same on the one-step predictions (empty: none given)
  std::vector<int> losses;     // per replay: how many others beat it
  // a's z over b that decides: the larger of z and z_one_step.
  double deciding(Eigen::Index a, Eigen::Index b) const {
    return z_one_step.size() ? std::max(z(a, b), z_one_step(a, b)) : z(a, b);
  }
};

// `replays`: the significant findings' replayed outputs (deviations, whole record), best score
// first; `measured`: the measured deviations. `one_step`: per replay, its model's one-step
// prediction (OneStepPrediction, audit_replay.hpp), or empty (none: the replays alone decide).
// Error when `replays` is empty or `one_step` is neither empty nor one per replay.
RivalChoice choose_among_rivals(const Eigen::MatrixXd& measured, const std::vector<const Eigen::MatrixXd*>& replays,
                                const Segment& validation, Eigen::Index covariance_lags, double margin,
                                const std::vector<OneStepPrediction>& one_step = {});

}  // namespace ambid::diag
