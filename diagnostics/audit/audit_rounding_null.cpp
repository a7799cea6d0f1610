#include "diagnostics/audit/audit_rounding_null.hpp"

#include <memory>
#include <random>

#include "core/controller_replay.hpp"
#include "core/error.hpp"
#include "diagnostics/audit/audit_replay.hpp"
#include "diagnostics/audit/audit_rounding.hpp"
#include "plant_sim/closed_loop.hpp"
#include "plant_sim/families.hpp"
#include "plant_sim/maglev_rig.hpp"

namespace ambid::diag {
namespace {

// `x` rounded column by column to multiples of resolution(j) shifted by offset(j) (unchanged
// where the resolution is 0).
Eigen::MatrixXd rounded_on_grid(const Eigen::MatrixXd& x, const Eigen::VectorXd& resolution,
                                const Eigen::VectorXd& offset) {
  Eigen::MatrixXd out = x;
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    if (resolution(j) > 0.0)
      for (Eigen::Index k = 0; k < x.rows(); ++k)
        out(k, j) = sim::round_to(x(k, j) + offset(j), resolution(j)) - offset(j);
  return out;
}

// The excitation that drove the record if the model with `effects` is right: the logged
// command less the controller's answer to the model's replayed output at full precision
// (deviations). The record's own r = u - C y_logged also holds -C q, the controller's answer to
// the logger's rounding q, which the rig's plant never had: a replica driven by it carries the
// record's rounding in its plant as well as its own in its r, and with a sensor delay at 1.3 ms
// its mean cross-spectrum with r missed the record's (the true model rejected, current
// coherence z 4.2 to 6.9 with 8 to 32 replicas).
Eigen::MatrixXd excitation_at_model(const Experiment& measured, const std::vector<sim::Effect>& effects) {
  const ReplayedLoop loop = replay_loop(measured, effects, measured.samples());
  Experiment at_model = measured;
  at_model.y = measured.y - measured.y_deviation() + loop.y;
  return measured.u_deviation() - replay_controller(at_model).output;
}

}  // namespace

std::vector<NullReplica> rounding_replicas(const Experiment& measured, const std::vector<sim::Effect>& effects,
                                           int count) {
  const Eigen::VectorXd y_resolution = logging_resolution(measured);
  const Eigen::VectorXd u_resolution = input_logging_resolution(measured);
  if (!(y_resolution.array() > 0.0).any() || count < 1) return {};
  const Eigen::Index N = measured.samples();
  Experiment header = measured;
  header.t.resize(0);
  header.y.resize(0, 0);
  header.u.resize(0, 0);
  header.r.resize(0, 0);
  Experiment full;
  try {
    const std::unique_ptr<sim::Plant> model =
        sim::plant_family(measured.plant.model, "audit").make_extended_plant(measured, effects);
    sim::ClosedLoopOptions options;
    options.samples = N;
    options.excitation = excitation_at_model(measured, effects);
    full = sim::run_closed_loop(*model, header, options);
  } catch (const InsufficientData&) {
    throw;
  } catch (const Error&) {
    return {};
  }
  std::vector<NullReplica> replicas;
  for (int m = 1; m <= count; ++m) {
    std::mt19937_64 rng{std::uint64_t(m)};
    std::uniform_real_distribution<double> fraction(0.0, 1.0);
    Eigen::VectorXd y_offset(y_resolution.size());
    for (Eigen::Index j = 0; j < y_offset.size(); ++j) y_offset(j) = fraction(rng) * y_resolution(j);
    // The command is rounded on the record's own grid: a DAC's levels (actuator_quantisation)
    // lie where they lie on it (a 0.35 V DAC's edges fall midway between the 0.01 V the rig
    // prints, so the record's commands never round across one), and a shifted grid gave the
    // replicas misrounded samples the record has not (their current residual 0.56 mA rms
    // against the record's 0.39 mA, at 1.5 ms).
    Experiment replica = full;
    replica.y = rounded_on_grid(full.y, y_resolution, y_offset);
    replica.u = rounded_on_grid(full.u, u_resolution, Eigen::VectorXd::Zero(u_resolution.size()));
    replica.r = replica.u_deviation() - replay_controller(replica).output;  // the operating value of r: 0
    try {
      const ReplayedLoop loop = replay_loop(replica, effects, N);
      replicas.push_back({replica.y_deviation() - loop.y, replica.r_deviation()});
    } catch (const InsufficientData&) {
      throw;
    } catch (const Error&) {
      continue;
    }
  }
  return replicas;
}

}  // namespace ambid::diag
