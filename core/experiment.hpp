#pragma once
// An experiment: uniformly sampled plant data plus what is known about the plant and the
// controller that closed the loop (experiment-format.md, version 1). Values are absolute, in SI
// units, as in the files; `deviations()` gives them relative to the operating point.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

namespace ambid {

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

  Eigen::Index states() const { return A.rows(); }
  // Throws Error when dimensions disagree, an entry is not finite, or D has a non-zero column
  // for a signal in `plant_inputs` (an algebraic loop through u).
  void validate(const std::vector<std::string>& plant_inputs) const;
};

struct PlantDescription {
  std::string model;                          // e.g. "amb1dof_voltage"
  std::map<std::string, double> parameters;   // nominal values the model believes
};

struct Experiment {
  std::string name;
  double sample_time = 0.0;
  PlantDescription plant;
  std::vector<std::string> y_names, u_names, r_names;  // r_names empty: no excitation recorded
  std::map<std::string, double> operating_point;       // missing signal: operating value 0
  std::optional<StateSpaceController> controller;

  Eigen::VectorXd t;     // seconds, one entry per sample
  Eigen::MatrixXd y, u, r;  // samples x signals, absolute values, columns in *_names order

  nlohmann::json extra;  // unknown sidecar keys, kept so a rewrite loses nothing

  Eigen::Index samples() const { return t.size(); }
  bool has_excitation() const { return !r_names.empty(); }
  double operating_value(const std::string& signal) const;
  Eigen::VectorXd operating_values(const std::vector<std::string>& signals) const;

  // Signals minus their operating values, same layout as y, u, r.
  Eigen::MatrixXd y_deviation() const;
  Eigen::MatrixXd u_deviation() const;
  Eigen::MatrixXd r_deviation() const;

  // The column of any named y/u/r signal (absolute). Throws Error for an unknown name.
  Eigen::VectorXd signal(const std::string& name) const;

  // Throws Error naming the first violation of the contract (dimensions, names, sampling).
  void validate() const;
};

}  // namespace ambid
