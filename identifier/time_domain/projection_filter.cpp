#include "identifier/time_domain/projection_filter.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "identifier/time_domain/kalman_gain.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;

// F from -F [B, AB, ..., A^(k-1) B] = [Z_1, ..., Z_k] by QR least squares.
Eigen::MatrixXd feedback_gain(const DiscreteSystem& sys, const MarkovSequence& z, Index count,
                              const LeastSquaresOptions& options) {
  const Index n = sys.states(), m = sys.inputs();
  Eigen::MatrixXd phi(count * m, n), target(count * m, m);
  Eigen::MatrixXd AkB = sys.B;
  for (Index k = 0; k < count; ++k) {
    phi.middleRows(k * m, m) = AkB.transpose();
    target.middleRows(k * m, m) = -z[static_cast<std::size_t>(k + 1)].transpose();
    AkB = sys.A * AkB;
  }
  std::vector<std::string> names;
  for (Index j = 0; j < n; ++j) names.push_back("state " + std::to_string(j + 1));
  LeastSquaresAccumulator acc(n, m, names);
  acc.add(phi, target);
  return acc.solve(options).theta.transpose();
}

}  // namespace

ProjectionFilterResult identify_projection_filter(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                                                  const Eigen::MatrixXd& uf, const ProjectionFilterOptions& options) {
  const Index p = y.cols(), m = u.cols(), J = options.markov_count;
  if (u.rows() != y.rows() || uf.rows() != y.rows() || uf.cols() != m)
    throw Error("projection filter: y " + dims(y) + ", u " + dims(u) + " and uf " + dims(uf) +
                " must have the same samples, and uf one column per plant input");
  if (p < 1 || m < 1) throw Error("projection filter: needs at least one output and one input channel");
  if (options.arx_order < 1)
    throw Error("projection filter: arx_order must be >= 1, got " + std::to_string(options.arx_order));
  if (J < 2) throw Error("projection filter: markov_count must be >= 2, got " + std::to_string(J));
  if (!(options.sample_time > 0.0)) throw Error("projection filter: sample_time must be positive");

  ProjectionFilterResult out;
  ArxOptions yo;
  yo.order = options.arx_order;
  yo.direct_term = options.estimate_feedthrough;
  yo.least_squares = options.least_squares;
  yo.breaks = options.breaks;
  out.output_arx = fit_arx(y, u, yo);
  ArxOptions fo = yo;
  fo.direct_term = false;
  out.feedback_arx = fit_arx(uf, y, u, fo);

  out.plant_markov = markov_from_arx(out.output_arx, J);
  out.feedback_markov = secondary_markov_from_arx(out.feedback_arx, out.plant_markov, J);

  if (!options.combined_realisation) {
    const EraResult e = era(out.plant_markov.system, options.sample_time, options.era);
    out.plant = e.system;
    out.hankel_singular_values = e.hankel_singular_values;
    out.suggested_order = e.suggested_order;
  } else {
    MarkovSequence combined;
    for (Index k = 0; k <= J; ++k) {
      Eigen::MatrixXd s(p + m, m + p);
      s << out.plant_markov.system[static_cast<std::size_t>(k)], out.plant_markov.gain[static_cast<std::size_t>(k)],
          out.feedback_markov.system[static_cast<std::size_t>(k)],
          out.feedback_markov.gain[static_cast<std::size_t>(k)];
      combined.push_back(s);
    }
    const EraResult e = era(combined, options.sample_time, options.era);
    out.hankel_singular_values = e.hankel_singular_values;
    out.suggested_order = e.suggested_order;
    out.plant.A = e.system.A;
    out.plant.B = e.system.B.leftCols(m);
    out.plant.C = e.system.C.topRows(p);
    out.plant.D = out.plant_markov.system[0];
    out.plant.sample_time = options.sample_time;
    out.predictor_gain = e.system.B.rightCols(p);
    out.feedback_gain = -e.system.C.bottomRows(m);
    if (const auto gain = linalg::regular_solve(out.plant.A, out.predictor_gain)) out.filter_gain = *gain;
    return out;
  }

  const Index n = out.plant.states();
  Index count = options.gain_count;
  if (count == 0) count = std::min<Index>(J, (2 * n + std::min(p, m) - 1) / std::min(p, m) + 1);
  if (count > J)
    throw Error("projection filter: gain_count " + std::to_string(count) + " exceeds markov_count " +
                std::to_string(J));
  const KalmanGainEstimate k =
      kalman_gain_from_markov(out.plant.A, out.plant.C, out.plant_markov.gain, count, options.least_squares);
  out.predictor_gain = k.predictor_gain;
  out.filter_gain = k.filter_gain;
  out.feedback_gain = feedback_gain(out.plant, out.feedback_markov.system, count, options.least_squares);
  return out;
}

}  // namespace ambid::ident
