#include "diagnostics/audit/audit_mode_search.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/linalg.hpp"

namespace ambid::diag {
namespace {

constexpr double kLowest = 100.0;       // Hz: below, the rigid-body loop itself
constexpr double kHighestShare = 0.95;  // of the Nyquist frequency
constexpr double kGridStep = 1.0025;    // 0.25 %: a quarter of the half-power band at zeta 0.005
// The matched filter leaves out the loop's reaction to q, which moves the resonance it sees:
// a mode at 276 Hz (near the loop's bandwidth) matched best at 287.5 Hz. So the replays span
// +-8 % in steps of 0.5 % (a third of the half-power band at zeta 0.015).
constexpr double kReplaySpan = 1.08, kReplayStep = 1.005;
constexpr double kMatchedZetas[] = {0.01, 0.03};
constexpr Eigen::Index kWhiteningOrder = 10;

// The prediction-error filter A(z) of an AR model of `e` fitted by least squares (QR): A e is
// nearly white, so that the matched filter weighs every frequency by the residual's own
// noise level, not by the loop-shaped low-frequency noise that dominates it.
Eigen::VectorXd whitening_filter(const Eigen::VectorXd& e) {
  const Eigen::Index p = kWhiteningOrder, n = e.size() - p;
  Eigen::MatrixXd lagged(n, p);
  for (Eigen::Index j = 0; j < p; ++j) lagged.col(j) = e.segment(p - 1 - j, n);
  const Eigen::VectorXd coefficients = linalg::qr_solve(lagged, Eigen::VectorXd(e.tail(n))).x;
  Eigen::VectorXd a(p + 1);
  a << 1.0, -coefficients;
  return a;
}

Eigen::VectorXd apply_fir(const Eigen::VectorXd& a, const Eigen::VectorXd& x) {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(x.size());
  for (Eigen::Index k = 0; k < x.size(); ++k)
    for (Eigen::Index j = 0; j < a.size() && j <= k; ++j) y[k] += a[j] * x[k - j];
  return y;
}

// q = H(s) a with H = 1 / (s^2 + 2 zeta w s + w^2), bilinear with prewarping at w.
Eigen::VectorXd resonance(const Eigen::VectorXd& a, double f, double zeta, double dt) {
  const double w = 2.0 * std::numbers::pi * f, K = w / std::tan(0.5 * w * dt);
  const double a0 = K * K + 2.0 * zeta * w * K + w * w;
  const double b0 = 1.0 / a0, b1 = 2.0 / a0, b2 = 1.0 / a0;
  const double a1 = (2.0 * w * w - 2.0 * K * K) / a0, a2 = (K * K - 2.0 * zeta * w * K + w * w) / a0;
  Eigen::VectorXd q(a.size());
  double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    const double y = b0 * a[k] + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
    x2 = x1, x1 = a[k], y2 = y1, y1 = y;
    q[k] = y;
  }
  return q;
}

}  // namespace

double matched_mode_frequency(const Eigen::VectorXd& residual_x, const Eigen::VectorXd& nominal_x, double sample_time,
                              const Segment& estimation) {
  const Eigen::Index n = estimation.end;
  // x'' of the nominal replay by central differences (0 at the ends).
  Eigen::VectorXd acceleration = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 1; k + 1 < n; ++k)
    acceleration[k] = (nominal_x[k + 1] - 2.0 * nominal_x[k] + nominal_x[k - 1]) / (sample_time * sample_time);
  // Zero where a controller clamp acted (before and after whitening): the match sums over the
  // kept samples.
  const Eigen::VectorXd kept = estimation.kept();
  const Eigen::VectorXd raw = estimation.kept_rows(residual_x);
  const Eigen::VectorXd whitening = whitening_filter(raw);
  const Eigen::VectorXd e = apply_fir(whitening, raw).cwiseProduct(kept);
  const double highest = kHighestShare * 0.5 / sample_time;
  double best_f = kLowest, best_explained = -1.0;
  for (double zeta : kMatchedZetas)
    for (double f = kLowest; f <= highest; f *= kGridStep) {
      const Eigen::VectorXd q = apply_fir(
          whitening, resonance(acceleration, f, zeta, sample_time).segment(estimation.begin, estimation.size()));
      const double qq = q.squaredNorm();
      if (!(qq > 0.0)) continue;
      const double eq = e.dot(q), explained = eq * eq / qq;
      if (explained > best_explained) best_explained = explained, best_f = f;
    }
  return best_f;
}

ModeStart search_mode_start(const Experiment& measured, const Eigen::MatrixXd& measured_y,
                            const Eigen::MatrixXd& nominal_y, const Segment& estimation,
                            const std::vector<double>& peaks) {
  const sim::EffectSpec& spec = sim::effect_spec("flexible_mode");
  auto spec_of = [&](const char* name) {
    return *std::find_if(spec.parameters.begin(), spec.parameters.end(),
                         [&](const sim::EffectParameterSpec& p) { return p.name == name; });
  };
  const double coupling = spec_of("coupling").scale, zeta = spec_of("zeta").neutral;
  const double highest = kHighestShare * 0.5 / measured.sample_time;
  const double matched =
      matched_mode_frequency(measured_y.col(0) - nominal_y.col(0), nominal_y.col(0), measured.sample_time, estimation);
  std::vector<double> frequencies = peaks;
  for (double f = matched / kReplaySpan; f <= matched * kReplaySpan; f *= kReplayStep) frequencies.push_back(f);
  ModeStart best{{}, INFINITY};
  for (double f : frequencies)
    for (double sign : {1.0, -1.0}) {
      if (!(f >= kLowest && f <= highest)) continue;
      const sim::Effect e =
          sim::make_effect("flexible_mode", {{"coupling", sign * coupling}, {"f", f}, {"zeta", zeta}});
      const double cost = estimation_cost(measured, measured_y, {e}, estimation);
      if (cost < best.cost || best.effect.name.empty()) best = {e, cost};
    }
  return best;
}

}  // namespace ambid::diag
