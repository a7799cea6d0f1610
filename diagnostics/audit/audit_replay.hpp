#pragma once
// The audit's view of a model: simulated in closed loop with the recorded controller and
// driven by the recorded excitation r (experiment-format.md, audit report), compared with the
// measurement by the contract's NRMSE.
#include <cstddef>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag {

// Samples [begin, end) of a record.
struct Segment {
  Eigen::Index begin = 0, end = 0;
  // Per sample of the record: a controller clamp acted there (not exogenous), so the NRMSE
  // scores leave it out. Empty: none.
  std::vector<bool> left_out{};
  Eigen::Index size() const { return end - begin; }
  bool left_out_at(Eigen::Index k) const { return k < std::ssize(left_out) && left_out[std::size_t(k)]; }
  // Per row of the segment: 1, or 0 where the sample is left out.
  Eigen::VectorXd kept() const;
  // The segment's rows of `x` (at least `end` rows), the left-out ones set to zero: a sum of
  // products or squares over them then leaves those samples out.
  Eigen::MatrixXd kept_rows(const Eigen::MatrixXd& x) const;
};

// The nominal model of the sidecar's plant family with `effects` of its catalogue (the family's
// extended simulator, plant_sim/families.hpp), replayed for the first `samples` samples;
// outputs as deviations from the operating point (samples x outputs). A record logged at a
// coarse resolution (audit_rounding.hpp) is followed: the controller reads the logged value
// while the model's output lies within half a step of it (ClosedLoopOptions::followed). Error when the
// experiment has no controller or no excitation, its family has no effect catalogue, or the
// model leaves its valid region (e.g. the rotor touches the bearing).
Eigen::MatrixXd replay_outputs(const Experiment& measured, const std::vector<sim::Effect>& effects,
                               Eigen::Index samples);

// What a replay gives the family's extended plant (diagnostics/plant_families.hpp,
// audit_replay_inputs): its effects, and what is added to the controller's output per sample
// (samples x controller outputs; e.g. a DAC's error on the logged command).
struct ReplayInputs {
  std::vector<sim::Effect> plant_effects;
  Eigen::MatrixXd input_offset;
};

// A family's one-step prediction of outputs its model predicts from the record alone, one
// sample ahead (diagnostics/plant_families.hpp, audit_one_step_prediction): per sample k the
// logged value at k + 1 (`measured`) and the model's prediction (`predicted`), deviations,
// samples x predicted outputs; both empty for a family without. The audit's head to head
// (audit_rivals.hpp) tests rivals on it besides their replays.
struct OneStepPrediction {
  Eigen::MatrixXd measured, predicted;
};

// The same replay with the plant inputs the recorded controller commanded in it (without the
// input offset).
struct ReplayedLoop {
  Eigen::MatrixXd y;  // samples x outputs, deviations
  Eigen::MatrixXd u;  // samples x inputs, deviations
};
ReplayedLoop replay_loop(const Experiment& measured, const std::vector<sim::Effect>& effects, Eigen::Index samples);

// Per output j: ||y_meas - y_model|| / ||y_meas - mean(y_meas)|| over the samples of
// `segment` not left out; both matrices as deviations, at least `segment.end` rows. Error for a
// constant measured output or fewer than two scored samples.
Eigen::VectorXd nrmse(const Eigen::MatrixXd& measured, const Eigen::MatrixXd& model, const Segment& segment);

// Checks what the audit needs of an experiment (Error naming what is missing).
void require_auditable(const Experiment& measured);

}  // namespace ambid::diag
