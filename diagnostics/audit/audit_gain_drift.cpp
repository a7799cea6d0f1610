#include "diagnostics/audit/audit_gain_drift.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.hpp"
#include "diagnostics/audit/audit_whitening.hpp"
#include "diagnostics/plant_families.hpp"

namespace ambid::diag {
namespace audit_gain_drift {

constexpr double kProbe = 0.05;          // V/V: the gain step whose replay gives the sensitivity
constexpr Eigen::Index kDriftLags = 50;  // lag window of the whitened residual's covariances
constexpr Eigen::Index kMinPart = 200;   // kept samples per part at least

double normal_upper(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

// P(chi2(nu) > x), Wilson-Hilferty.
double chi_square_upper(double x, double nu) {
  const double v = 2.0 / (9.0 * nu);
  return normal_upper((std::cbrt(std::max(x, 0.0) / nu) - (1.0 - v)) / std::sqrt(v));
}

// sum_k a[k] b[k + h] over the samples where both exist.
double lagged(const Eigen::VectorXd& a, const Eigen::VectorXd& b, Eigen::Index h) {
  const Eigen::Index n = a.size();
  return h >= 0 ? a.head(n - h).dot(b.tail(n - h)) : a.tail(n + h).dot(b.head(n + h));
}

struct PartFit {
  Eigen::VectorXd theta, se;
};

// Per part [bounds[s], bounds[s + 1]): theta_s = <e, S>_w / <S, S>_w; with `noise` (the residual
// after the fit, whole record) also its standard error from the noise's auto/cross-covariances.
PartFit fit_parts(const Eigen::MatrixXd& e, const Eigen::MatrixXd& S, const Eigen::VectorXd& w,
                  const std::vector<Eigen::Index>& bounds, const Eigen::MatrixXd* noise) {
  const auto parts = Eigen::Index(bounds.size()) - 1;
  const Eigen::Index q = e.cols(), M = kDriftLags;
  PartFit f{Eigen::VectorXd::Zero(parts), Eigen::VectorXd::Zero(parts)};
  // gamma[(j q + l)](h + M): the noise's covariance of outputs j and l at lag h.
  Eigen::MatrixXd gamma;
  if (noise) {
    gamma.resize(q * q, 2 * M + 1);
    for (Eigen::Index j = 0; j < q; ++j)
      for (Eigen::Index l = 0; l < q; ++l)
        for (Eigen::Index h = -M; h <= M; ++h)
          gamma(j * q + l, h + M) = (1.0 - double(std::abs(h)) / double(M + 1)) *
                                    lagged(noise->col(j), noise->col(l), h) / double(noise->rows());
  }
  for (Eigen::Index s = 0; s < parts; ++s) {
    const Eigen::Index b = bounds[std::size_t(s)], n = bounds[std::size_t(s) + 1] - b;
    double num = 0.0, den = 0.0;
    for (Eigen::Index j = 0; j < q; ++j) {
      num += w[j] * e.col(j).segment(b, n).dot(S.col(j).segment(b, n));
      den += w[j] * S.col(j).segment(b, n).squaredNorm();
    }
    f.theta[s] = den > 0.0 ? num / den : 0.0;
    if (!noise || !(den > 0.0)) continue;
    double variance = 0.0;
    for (Eigen::Index j = 0; j < q; ++j)
      for (Eigen::Index l = 0; l < q; ++l) {
        const Eigen::VectorXd sj = S.col(j).segment(b, n), sl = S.col(l).segment(b, n);
        for (Eigen::Index h = -M; h <= M; ++h) variance += w[j] * w[l] * gamma(j * q + l, h + M) * lagged(sj, sl, h);
      }
    f.se[s] = std::sqrt(std::max(variance, 0.0)) / den;
  }
  return f;
}

// The residual of `e` after the per-part fit `theta` of S.
Eigen::MatrixXd after_parts(const Eigen::MatrixXd& e, const Eigen::MatrixXd& S, const Eigen::VectorXd& theta,
                            const std::vector<Eigen::Index>& bounds) {
  Eigen::MatrixXd r = e;
  for (Eigen::Index s = 0; s + 1 < Eigen::Index(bounds.size()); ++s) {
    const Eigen::Index b = bounds[std::size_t(s)], n = bounds[std::size_t(s) + 1] - b;
    r.middleRows(b, n) -= theta[s] * S.middleRows(b, n);
  }
  return r;
}

GainDriftChannel test_channel(int channel, const Eigen::MatrixXd& e, const Eigen::MatrixXd& S, const Segment& record,
                              const std::vector<Eigen::Index>& bounds) {
  const Eigen::Index q = e.cols();
  // First pass, unwhitened (outputs by their residual's spread), for the noise model only.
  Eigen::VectorXd w(q);
  for (Eigen::Index j = 0; j < q; ++j) w[j] = 1.0 / std::max(e.col(j).squaredNorm(), 1e-300);
  const PartFit first = fit_parts(e, S, w, bounds, nullptr);
  const Segment whole{0, e.rows(), {}};
  const NoiseWhitening whitening = fit_noise_whitening(after_parts(e, S, first.theta, bounds), whole);
  Segment mask = record;
  mask.begin = 0;
  mask.end = e.rows();
  const Eigen::MatrixXd we = mask.kept_rows(whitening.apply(e)), wS = mask.kept_rows(whitening.apply(S));
  const Eigen::MatrixXd white_noise = after_parts(we, wS, fit_parts(we, wS, w, bounds, nullptr).theta, bounds);
  for (Eigen::Index j = 0; j < q; ++j) w[j] = 1.0 / std::max(white_noise.col(j).squaredNorm(), 1e-300);
  const PartFit f = fit_parts(we, wS, w, bounds, &white_noise);
  GainDriftChannel c;
  c.channel = channel;
  c.gain = f.theta;
  c.se = f.se;
  if (!(f.se.array() > 0.0).all()) return c;
  const Eigen::VectorXd weight = f.se.array().square().inverse();
  const double mean = weight.dot(f.theta) / weight.sum();
  c.q = (weight.array() * (f.theta.array() - mean).square()).sum();
  c.q_p = chi_square_upper(c.q, double(f.theta.size() - 1));
  const auto parts = f.theta.size();
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(parts, 0.0, double(parts - 1));
  t.array() -= weight.dot(t) / weight.sum();
  const double sxx = (weight.array() * t.array().square()).sum();
  c.slope_z = (weight.array() * t.array() * (f.theta.array() - mean)).sum() / std::sqrt(sxx);
  c.slope_p = 2.0 * normal_upper(std::abs(c.slope_z));
  c.p_value = std::min(1.0, 2.0 * std::min(c.q_p, c.slope_p));
  return c;
}

}  // namespace audit_gain_drift

GainDrift gain_drift_test(const Experiment& measured, const Eigen::MatrixXd& measured_y,
                          const std::vector<sim::Effect>& effects, const Eigen::MatrixXd& model_y,
                          const Segment& record, bool rounded, int segments, double alpha) {
  using namespace audit_gain_drift;
  if (segments < 3) throw Error("audit: the gain drift test needs at least 3 parts, got " + std::to_string(segments));
  if (!(alpha > 0.0 && alpha < 1.0))
    throw Error("audit: gain drift test probability must be in (0, 1), got " + std::to_string(alpha));
  GainDrift d;
  d.segments = segments;
  d.alpha = alpha;
  const std::vector<sim::EffectSpec>& catalogue = effect_catalogue_of(measured.plant.model, "audit");
  const auto spec = std::find_if(catalogue.begin(), catalogue.end(),
                                 [](const sim::EffectSpec& s) { return s.name == "amplifier_gain"; });
  if (spec == catalogue.end()) {
    d.reason = "the family has no amplifier_gain effect";
    return d;
  }
  if (rounded) {
    d.reason = "the record is logged at a coarse resolution: its replay follows the rounding";
    return d;
  }
  // segments + 1 parts, the first left out (the start from the operating point, where the
  // replay's sensitivity is largest and any model error shows most).
  const Eigen::Index N = record.end - record.begin;
  std::vector<Eigen::Index> bounds;
  for (int s = 1; s <= segments + 1; ++s) bounds.push_back(record.begin + N * s / (segments + 1));
  for (int s = 0; s < segments; ++s) {
    const Segment part{bounds[std::size_t(s)], bounds[std::size_t(s) + 1], record.left_out};
    if (part.kept().sum() < double(kMinPart)) {
      d.reason = "a part holds fewer than " + std::to_string(kMinPart) + " samples without a controller clamp";
      return d;
    }
  }
  d.determinable = true;
  Segment whole = record;
  whole.begin = 0;
  whole.end = measured_y.rows();
  const Eigen::MatrixXd e = whole.kept_rows(measured_y - model_y);
  for (int channel : spec->has_channel ? std::vector<int>{1, 2} : std::vector<int>{0}) {
    std::vector<sim::Effect> probed = effects;
    std::map<std::string, double> values{{"dkw", kProbe}};
    if (channel) values["channel"] = channel;
    probed.push_back(sim::make_effect(catalogue, "amplifier_gain", values));
    Eigen::MatrixXd y;
    try {
      y = replay_outputs(measured, probed, measured_y.rows());
    } catch (const InsufficientData&) {
      throw;
    } catch (const Error&) {
      continue;  // the probed gain cannot be replayed: no sensitivity for this amplifier
    }
    const Eigen::MatrixXd S = whole.kept_rows((y - model_y) / kProbe);
    d.channels.push_back(test_channel(channel, e, S, record, bounds));
  }
  if (d.channels.empty()) return d;
  const auto best =
      std::min_element(d.channels.begin(), d.channels.end(),
                       [](const GainDriftChannel& a, const GainDriftChannel& b) { return a.p_value < b.p_value; });
  d.p_value = std::min(1.0, best->p_value * double(d.channels.size()));
  d.varies = d.p_value < alpha;
  if (d.varies) d.channel = best->channel;
  return d;
}

}  // namespace ambid::diag
