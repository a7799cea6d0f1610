#include "diagnostics/audit/audit_replay.hpp"

#include <algorithm>
#include <memory>
#include <string>

#include "core/error.hpp"
#include "diagnostics/audit/audit_rounding.hpp"
#include "diagnostics/plant_families.hpp"
#include "plant_sim/closed_loop.hpp"
#include "plant_sim/families.hpp"

namespace ambid::diag {

void require_auditable(const Experiment& measured) {
  require_diagnostics_piece(measured.plant.model, DiagnosticsPiece::effect_catalogue, "audit");
  if (!measured.controller) throw Error("audit: the experiment has no controller, so the loop cannot be replayed");
  if (!measured.has_excitation())
    throw InsufficientData("audit: the experiment records no excitation r, so the loop cannot be replayed");
  if (measured.samples() < 100)
    throw InsufficientData("audit: " + std::to_string(measured.samples()) + " samples are too few (need at least 100)");
}

ReplayedLoop replay_loop(const Experiment& measured, const std::vector<sim::Effect>& effects, Eigen::Index samples) {
  require_auditable(measured);
  if (samples < 1 || samples > measured.samples())
    throw Error("audit: cannot replay " + std::to_string(samples) + " of " + std::to_string(measured.samples()) +
                " samples");
  const ReplayInputs inputs = audit_replay_inputs(measured, effects, samples);
  const std::unique_ptr<sim::Plant> model =
      sim::plant_family(measured.plant.model, "audit").make_extended_plant(measured, inputs.plant_effects);
  sim::ClosedLoopOptions options;
  options.samples = samples;
  options.excitation = measured.r_deviation().topRows(samples) + inputs.input_offset;
  const Eigen::VectorXd resolution = logging_resolution(measured);
  if ((resolution.array() > 0.0).any()) {
    options.followed = measured.y.topRows(samples);
    options.followed_resolution = resolution;
  }
  Experiment header = measured;
  header.t.resize(0);
  header.y.resize(0, 0);
  header.u.resize(0, 0);
  header.r.resize(0, 0);
  const Experiment replayed = sim::run_closed_loop(*model, header, options);
  // The commands the controller gave, without what the record added to them (audit_replay_inputs).
  Eigen::MatrixXd u = replayed.u_deviation();
  const auto& names = measured.controller->outputs;
  for (std::size_t j = 0; j < names.size(); ++j) {
    const auto signal = std::find(measured.u_names.begin(), measured.u_names.end(), names[j]);
    if (signal != measured.u_names.end())
      u.col(signal - measured.u_names.begin()) -= inputs.input_offset.col(Eigen::Index(j));
  }
  return {replayed.y_deviation(), u};
}

Eigen::MatrixXd replay_outputs(const Experiment& measured, const std::vector<sim::Effect>& effects,
                               Eigen::Index samples) {
  return replay_loop(measured, effects, samples).y;
}

Eigen::VectorXd Segment::kept() const {
  Eigen::VectorXd k = Eigen::VectorXd::Ones(size());
  for (Eigen::Index i = begin; i < end; ++i)
    if (left_out_at(i)) k(i - begin) = 0.0;
  return k;
}

Eigen::MatrixXd Segment::kept_rows(const Eigen::MatrixXd& x) const {
  if (begin < 0 || x.rows() < end)
    throw Error("audit: segment [" + std::to_string(begin) + ", " + std::to_string(end) +
                ") does not fit a signal of " + std::to_string(x.rows()) + " samples");
  return kept().asDiagonal() * x.middleRows(begin, size());
}

Eigen::VectorXd nrmse(const Eigen::MatrixXd& measured, const Eigen::MatrixXd& model, const Segment& segment) {
  if (segment.begin < 0 || segment.size() < 2 || measured.rows() < segment.end || model.rows() < segment.end ||
      measured.cols() != model.cols())
    throw Error("audit: NRMSE segment [" + std::to_string(segment.begin) + ", " + std::to_string(segment.end) +
                ") does not fit the signals");
  const Eigen::VectorXd kept = segment.kept();  // 0 where a sample is left out
  if (kept.sum() < 2.0) throw InsufficientData("audit: fewer than two samples without a controller clamp to score");
  const Eigen::MatrixXd m = measured.middleRows(segment.begin, segment.size());
  const Eigen::MatrixXd e = (m - model.middleRows(segment.begin, segment.size())).array().colwise() * kept.array();
  Eigen::VectorXd out(m.cols());
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    const double mean = m.col(j).dot(kept) / kept.sum();
    const double spread = ((m.col(j).array() - mean) * kept.array()).matrix().norm();
    if (!(spread > 0.0)) throw InsufficientData("audit: measured output " + std::to_string(j + 1) + " is constant");
    out[j] = e.col(j).norm() / spread;
  }
  return out;
}

}  // namespace ambid::diag
