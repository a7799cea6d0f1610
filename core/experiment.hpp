#pragma once
// An experiment: uniformly sampled plant data plus what is known about the plant and the
// controller that closed the loop (experiment-format.md, version 1). Values are absolute, in SI
// units, as in the files; the *_deviation() methods give them relative to the operating point.
//
// Error messages name the offending field by its sidecar key path (`signals.u`,
// `controller.B`, `operating_point.x`), so the file reader only has to prefix the file name.
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/json_value.hpp"

namespace ambid {

// A clamp [lo, hi]; an infinite bound is no bound on that side (null in the sidecar).
struct Limit {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool acts_on(double value) const { return value <= lo || value >= hi; }  // at or beyond a bound
};

// The discrete controller that closed the loop:
//   xc[k+1] = A xc[k] + B v[k],  uf[k] = C xc[k] + D v[k],  u[k] = uf[k] + r[k]  (deviations)
// where v stacks the deviations of the signals named in `inputs` at sample k and `outputs`
// names the plant inputs that uf drives.
struct StateSpaceController {
  std::string kind = "state_space";
  double sample_time = 0.0;
  std::vector<std::string> inputs;
  std::vector<std::string> outputs;
  Eigen::MatrixXd A, B, C, D;
  Eigen::VectorXd initial_state;  // empty means zero
  // Optional clamps (controller.output_limits, state_limits): one per output, on the plant
  // input in absolute units, and one per state, in deviations. Empty: none.
  std::vector<Limit> output_limits, state_limits;

  Eigen::Index states() const { return A.rows(); }
  // Throws Error when the kind is not "state_space", the sample time is not positive and
  // finite, inputs/outputs are empty or repeat a name, an output is not in `plant_inputs`,
  // dimensions disagree, an entry is not finite, a limit list has the wrong length or a limit
  // with lo >= hi or NaN, or D has a non-zero column for a signal in
  // `plant_inputs` (an algebraic loop through u).
  void validate(const std::vector<std::string>& plant_inputs) const;
};

struct PlantDescription {
  std::string model;                         // e.g. "amb1dof_voltage"
  std::map<std::string, double> parameters;  // nominal values the model believes
};

// Sampling is uniform when every step t[k] - t[k-1] is within this fraction of sample_time.
inline constexpr double kSamplingTolerance = 0.01;

// The first index k >= 1 whose step t[k] - t[k-1] is outside sample_time * (1 +- 1 %), or
// nullopt when the sampling is uniform.
std::optional<Eigen::Index> find_sampling_gap(const Eigen::VectorXd& t, double sample_time);

struct Experiment {
  std::string name;
  double sample_time = 0.0;
  PlantDescription plant;
  std::vector<std::string> y_names, u_names, r_names;  // r_names empty: no excitation recorded
  // Every y and u signal has an entry (validate() insists); r signals default to 0. Entries
  // for names that are no signal are kept (they may describe ignored CSV columns).
  std::map<std::string, double> operating_point;
  std::optional<StateSpaceController> controller;

  Eigen::VectorXd t;        // seconds, one entry per sample
  Eigen::MatrixXd y, u, r;  // samples x signals, absolute values, columns in *_names order

  // Unknown sidecar keys, kept so a rewrite loses nothing. Mirrors the sidecar: top-level
  // unknown keys at the top, unknown keys inside `plant`, `signals` or `controller` under an
  // object of that name. It never holds a key the format defines.
  JsonValue extra;

  Eigen::Index samples() const { return t.size(); }
  bool has_excitation() const { return !r_names.empty(); }
  // y, then u, then r names: the CSV column order after `t`.
  std::vector<std::string> signal_names() const;
  double operating_value(const std::string& signal) const;  // 0 when not listed
  Eigen::VectorXd operating_values(const std::vector<std::string>& signals) const;

  // Signals minus their operating values, same layout as y, u, r.
  Eigen::MatrixXd y_deviation() const;
  Eigen::MatrixXd u_deviation() const;
  Eigen::MatrixXd r_deviation() const;

  // The column of any named y/u/r signal (absolute). Throws Error for an unknown name.
  Eigen::VectorXd signal(const std::string& name) const;

  // Throws Error naming the first violation of the contract among the sidecar fields
  // (names, sample time, parameters, operating point, controller, extra); ignores samples.
  void validate_metadata() const;
  // validate_metadata() plus the samples: at least 2, matrix shapes match the names, all
  // finite, t strictly increasing and uniform within kSamplingTolerance.
  void validate() const;
};

}  // namespace ambid
